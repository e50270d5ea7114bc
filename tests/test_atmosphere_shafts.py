"""Rendered sun shafts: the dust under an occluder is darker than the dust in the sun, and with
wind-lifted dust the open ground glows only where dust is.

Top-down orthographic view of black ground; the sun straight overhead; a roof over x < 0
at 3 m that the camera does not see but that casts its shadow; the sky switched off, so
every pixel is light the volume scattered.
"""

import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

SIZE = 48


@pytest.fixture
def shaft_scene():
    def build(**atmosphere):
        ground = readback.uv_plane(20.0, "Ground")
        # Reflects nothing: even a black BSDF has a specular glint.
        ground.data.materials.append(scenes.single_node_material("Black", "ShaderNodeEmission", Strength=0.0))
        bpy.ops.mesh.primitive_plane_add(size=1.0, location=(-5.0, 0.0, 3.0))
        roof = bpy.context.active_object
        roof.scale = (10.0, 20.0, 1.0)
        roof.visible_camera = False
        settings = bpy.context.scene.sandscape_atmosphere
        settings.sun_elevation, settings.margin = math.radians(90.0), 1.0
        for key, value in atmosphere.items():
            setattr(settings, key, value)
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        for background in (n for n in bpy.context.scene.world.node_tree.nodes if n.type == "BACKGROUND"):
            background.inputs["Strength"].default_value = 0.0  # the sun alone lights the dust
        scene = readback.cycles_scene(resolution=(SIZE, SIZE), samples=32)
        scene.cycles.volume_biased = True  # ray marching: a noise density renders in a fraction of the time
        scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=16.0)
        pixels = readback.render(scene)[..., :3].sum(-1)
        x = (np.arange(SIZE) + 0.5) / SIZE * 16.0 - 8.0
        return pixels[:, (x > -6) & (x < -2)], pixels[:, (x > 2) & (x < 6)]
    return build


def test_shadowed_dust_is_darker_than_lit_dust(shaft_scene):
    shadowed, lit = shaft_scene(density=0.05, use_wind=False)
    contrast = 1.0 - shadowed.mean() / lit.mean()
    # Under the roof only the metre of dust above it is lit, against five metres in the open.
    assert contrast > 0.6, contrast
    assert np.isfinite(shadowed).all() and np.isfinite(lit).all()


def test_wind_lifted_dust_glows_only_in_patches(shaft_scene):
    _, homogeneous = shaft_scene(density=0.05, use_wind=False)
    bpy.ops.wm.read_homefile(use_empty=True)
    _, patchy = shaft_scene(density=0.05, use_wind=True, coverage=0.4, dust_scale=3.0, softness=0.02,
                            falloff=50.0)
    level = 0.1 * homogeneous.mean()
    assert (homogeneous < level).mean() < 0.01  # homogeneous dust: light everywhere
    clear = (patchy < level).mean()
    assert 0.2 < clear < 0.95, clear  # clear ground between the patches, and patches
