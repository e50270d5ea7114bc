"""The sun lamp Add Atmosphere makes lights like the sky model's own sun, so lamp and sky share
the ground's light as the sky model says, and lit sand keeps its colour.

Reference: the Sky Texture itself. A grey plane seen from above is rendered three times: lit by
the lamp alone (black world), by the sky with its sun disc for every ray (no lamp), and by the
disc-less sky that Add Atmosphere lights with (no lamp). The disc's light is the second minus
the third; the lamp must give the same.
"""

import colorsys
import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

ALBEDO = 0.5
ELEVATIONS = (10, 30, 60)
MATCH_TOLERANCE = 0.03  # per channel, lamp against disc: the disc's sampling noise at 1024 spp
SHARE_TOLERANCE = 0.02  # the direct share, against the table's (core/sun.py)
HUE_TOLERANCE = 10.0  # degrees: lit sand's hue against its base colour's


def grey_ground(elevation, sandscape):
    bpy.ops.mesh.primitive_plane_add(size=100)
    plane = bpy.context.active_object
    plane.data.materials.append(scenes.single_node_material("Grey", "ShaderNodeBsdfDiffuse",
                                                           Color=(ALBEDO, ALBEDO, ALBEDO, 1.0)))
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth, settings.density = math.radians(elevation), 0.3, 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene = readback.cycles_scene(resolution=(4, 4), samples=1024)
    scene.cycles.max_bounces = 1
    scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=1.0)
    return scene, sandscape.addon.atmosphere.scene_sun(scene)


def mean_render(scene):
    return readback.render(scene)[..., :3].astype(np.float64).mean((0, 1))


@pytest.mark.parametrize("elevation", ELEVATIONS)
def test_the_lamp_lights_like_the_skys_own_sun(sandscape, elevation):
    scene, sun = grey_ground(elevation, sandscape)
    world = scene.world
    sky, seen = (world.node_tree.nodes[n] for n in ("Sandscape Sky", "Sandscape Sky with Sun Disc"))
    scene.world = None
    lamp = mean_render(scene)
    scene.world, sun.hide_render = world, True
    sky_only = mean_render(scene)
    sky.sun_disc = True  # every ray sees the disc now, as sunlight
    disc = mean_render(scene) - sky_only
    assert np.abs(lamp / disc - 1.0).max() <= MATCH_TOLERANCE, (lamp, disc)
    direct, diffuse = sandscape.core.sun.level_irradiance(math.radians(elevation))
    share = lamp / (lamp + sky_only)
    expected = direct / (direct + diffuse)
    print(f"sun {elevation} deg: direct share {share.round(3)} (table {expected.round(3)})")
    assert np.abs(share - expected).max() <= SHARE_TOLERANCE
    assert seen.sun_disc  # the camera still sees the disc in the normal set-up


@pytest.mark.parametrize("elevation", (10, 30))
def test_lit_sand_keeps_its_colour(sandscape, elevation):
    scene, _ = grey_ground(elevation, sandscape)
    plane = bpy.context.active_object
    bpy.context.view_layer.objects.active = next(o for o in scene.objects if o.type == "MESH")
    plane.data.materials.clear()
    bpy.ops.sandscape.add_sand_material(strength=0.0)
    sand = mean_render(scene)
    base = sandscape.addon.sand.SAND_COLOR[:3]
    hue, saturation, _ = colorsys.rgb_to_hsv(*sand)
    base_hue = colorsys.rgb_to_hsv(*base)[0]
    difference = abs((hue - base_hue + 0.5) % 1.0 - 0.5) * 360.0
    print(f"sun {elevation} deg: lit sand hue {hue * 360:.1f}, base {base_hue * 360:.1f}, "
          f"R/B {sand[0] / sand[2]:.2f}")
    assert difference <= HUE_TOLERANCE and saturation > 0.3


def test_add_atmosphere_sets_lamp_and_exposure_from_the_sky(sandscape):
    bpy.ops.mesh.primitive_plane_add(size=10)
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation = math.radians(30)
    settings.set_exposure = True  # off by default: the exposure is the artist's
    bpy.ops.sandscape.add_atmosphere()
    sun = sandscape.addon.atmosphere.scene_sun(bpy.context.scene)
    strength, colour = sandscape.core.sun.lamp(math.radians(30))
    assert sun.data.energy == pytest.approx(strength, rel=1e-5)
    assert tuple(sun.data.color) == pytest.approx(colour, abs=1e-5)
    assert bpy.context.scene.view_settings.exposure == pytest.approx(
        sandscape.core.sun.exposure(math.radians(30)), abs=0.01)
    settings.sun_from_sky = settings.set_exposure = False
    sun.data.energy, bpy.context.scene.view_settings.exposure = 3.0, 0.5
    bpy.ops.sandscape.add_atmosphere()
    assert sun.data.energy == pytest.approx(3.0)
    assert bpy.context.scene.view_settings.exposure == pytest.approx(0.5)
