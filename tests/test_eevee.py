"""EEVEE renders, few and small (issue 27): EEVEE needs an OpenGL context, which the bpy wheel
opens through EGL, on software OpenGL here. Where none can be made these tests skip and say so."""

import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

SIZE = (64, 36)


@pytest.fixture
def eevee_scene():
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    scene.render.resolution_x, scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.eevee.taa_render_samples = 4
    probe = scenes.camera("PERSP")
    try:
        readback.render(scene)
    except RuntimeError as error:  # no OpenGL context: EEVEE cannot draw
        pytest.skip(f"EEVEE cannot render here (no OpenGL context: {error})")
    finally:
        bpy.data.objects.remove(probe)
    return scene


def test_god_rays_shine_from_the_sun_in_eevee(eevee_scene, sandscape):
    """The driven sun place and the rays work on EEVEE's own passes: the rays' glow peaks where
    Blender projects the sun."""
    scene = eevee_scene
    bpy.ops.mesh.primitive_plane_add(size=40)
    scenes.camera("PERSP", location=(0, -6, 1.0), rotation=(math.radians(88), 0, math.radians(-8)), lens=35)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(6), 0.0, 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene.sandscape_post.use_blur = scene.sandscape_post.use_denoise = False
    assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
    assert scene.render.engine == "BLENDER_EEVEE"
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    _, u, v, intensity = sandscape.addon.sun_screen.stepped_curve(scene, sun, 0.25)[0]
    assert intensity == 1.0 and 0.2 < u < 0.8 and 0.5 < v < 0.95  # in the frame, over the horizon
    with_rays = readback.render(scene)
    scene.render.use_compositing = False
    plain = readback.render(scene)
    assert np.isfinite(with_rays).all()
    rays = (with_rays - plain)[..., :3].sum(-1)
    assert rays.max() > 0.05  # they show
    row, col = np.unravel_index(np.argmax(rays), rays.shape)
    assert abs((col + 0.5) / SIZE[0] - u) < 0.08 and abs((row + 0.5) / SIZE[1] - v) < 0.12
