"""Clouds shaded in EEVEE as in Cycles (issue 27): a cloud's underside, turned from a low sun, is
grey in Cycles; EEVEE lit it with the whole sun (its Volume Shadows are off in a new file) and the
layer read as flat bright haze. The EEVEE presets turn the shadows on. Skipped, saying why, where
no OpenGL context can be made (the eevee_scene fixture)."""

import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

SIZE = (64, 36)
LEAST_CORRELATION = 0.5  # of the sky's luminance, pixel by pixel, with Cycles'


def _cloud_view(scene, sandscape):
    """Sand out to the horizon, Add Atmosphere's sky with a 20 degree sun off to the right, Add
    Clouds over it, and a camera 1.5 m up looking 15 degrees above the horizon; EEVEE with the Draft
    preset, Cycles with its volume bounces. Returns the sky's pixels (rows bottom-up)."""
    scene.render.resolution_x, scene.render.resolution_y = SIZE
    bpy.ops.mesh.primitive_plane_add(size=1e5)  # the clouds' bases see lit sand below, in Cycles too
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Sand", "ShaderNodeBsdfDiffuse", Color=sandscape.core.sand.SAND_COLOR))
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 1.5), rotation=(math.radians(105.0), 0.0, 0.0),
                           lens=24.0)
    camera.data.clip_end = 1e5
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(20.0), math.radians(60.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert bpy.ops.sandscape.add_clouds(coverage=0.5, seed=0, voxel=400.0) == {"FINISHED"}
    presets = sandscape.addon.presets
    presets.apply_eevee(scene, presets.EEVEE_PRESETS["DRAFT"])
    scene.eevee.taa_render_samples = 4
    scene.cycles.samples = 8
    scene.cycles.volume_bounces = scene.cycles.max_bounces = presets.PRESETS["DRAFT"]["volume_bounces"]
    return ~scenes.pixel_hits(scene, camera, *SIZE, (0.0, 0.0, 1.0))["hit"]


def _sky_luminance(scene, engine, sky):
    scene.render.engine = engine
    seen = readback.render(scene)[..., :3]
    assert np.isfinite(seen).all()
    return seen.astype(np.float64).mean(-1)[sky]


def _correlation(a, b):
    return float(np.corrcoef(a, b)[0, 1])


def test_clouds_are_shaded_in_eevee_as_in_cycles(eevee_scene, sandscape):
    """The sky's luminance in EEVEE under the Draft preset, pixel by pixel, against Cycles'
    (8 samples): correlated at 0.5 or more. When written: 0.690 on 5.2, 0.916 on 5.0 (without
    the shadows 0.139 and 0.448: the sweep below). The brightness is not asserted: EEVEE's sky is
    1.28 times Cycles' mean on 5.2, 0.69 times on 5.0 (README, *The clouds shade themselves*)."""
    sky = _cloud_view(eevee_scene, sandscape)
    cycles = _sky_luminance(eevee_scene, "CYCLES", sky)
    eevee = _sky_luminance(eevee_scene, "BLENDER_EEVEE", sky)
    correlation = _correlation(cycles, eevee)
    print(f"clouds in EEVEE: correlation {correlation:.3f} with Cycles, sky mean {eevee.mean():.3f} against "
          f"{cycles.mean():.3f}")
    assert sky.mean() > 0.5
    assert correlation >= LEAST_CORRELATION


@pytest.mark.sweep  # one more EEVEE render: without the presets' shadows the match falls
def test_without_volume_shadows_eevee_clouds_are_further_from_cycles(eevee_scene, sandscape):
    sky = _cloud_view(eevee_scene, sandscape)
    cycles = _sky_luminance(eevee_scene, "CYCLES", sky)
    shaded = _correlation(cycles, _sky_luminance(eevee_scene, "BLENDER_EEVEE", sky))
    eevee_scene.eevee.use_volumetric_shadows = False
    flat = _sky_luminance(eevee_scene, "BLENDER_EEVEE", sky)
    print(f"clouds in EEVEE: correlation {shaded:.3f} with Cycles, {_correlation(cycles, flat):.3f} without "
          f"volume shadows (sky mean {cycles.mean():.3f} in Cycles, {flat.mean():.3f} without)")
    assert shaded - _correlation(cycles, flat) >= 0.25
