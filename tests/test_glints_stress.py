"""Extreme glint settings never put NaN or Inf in a pixel, through Blender and through the twin."""

import math

import bpy
import numpy as np
import pytest

from core import glints as twin
from devtools import readback, scenes

EXTREMES = [
    {"facing_power": 0.0},  # 0^0 at the grazing silhouette
    {"facing_power": 1e6},
    {"strength": 1e6},
    {"glint_size": 1e-6},
    {"glint_size": 1e6},
    {"threshold": 0.0, "facing_power": 1e6, "strength": 1e6, "glint_size": 1e-6},
]


def grazing_scene(material_props):
    readback.cycles_scene(resolution=(48, 32), samples=4)
    ground = readback.uv_plane(200.0, "Ground")
    assert bpy.ops.sandscape.add_sand_material(**material_props) == {"FINISHED"}
    scenes.analytic_sphere(ground.active_material, 1.0, location=(0.0, 20.0, 1.0))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.rotation_euler = (math.radians(80), 0.0, 0.0)
    bpy.context.scene.collection.objects.link(sun)
    # Eye 5 cm above the ground: the far ground is seen at grazing angles.
    scenes.camera("PERSP", location=(0.0, 0.0, 0.05), rotation=(math.radians(89.5), 0.0, 0.0))


@pytest.mark.parametrize("props", EXTREMES, ids=lambda p: ",".join(f"{k}={v:g}" for k, v in p.items()))
def test_extreme_settings_render_finite(sandscape, props):
    grazing_scene(props)
    pixels = readback.render()
    assert np.isfinite(pixels).all()
    assert pixels[..., :3].max() > 0.0  # the ground and the sphere are lit


@pytest.mark.parametrize("output", ["Mask", "Glint Color"])
def test_group_outputs_finite_even_with_a_linked_negative_power(glints_group, output):
    """Sockets clamp typed values but not linked ones: the group clamps the power itself."""
    readback.cycles_scene(resolution=(32, 32), samples=1)
    material = scenes.group_material(glints_group, {"Threshold": 0.0, "Strength": 1e6}, output)
    node = next(n for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeGroup")
    negative = material.node_tree.nodes.new("ShaderNodeValue")
    negative.outputs[0].default_value = -5.0
    material.node_tree.links.new(negative.outputs[0], node.inputs["Facing Power"])
    scenes.analytic_sphere(material, 1.0)
    scenes.camera("ORTHO", ortho_scale=2.2)
    pixels = readback.render()
    assert np.isfinite(pixels).all()
    if output == "Mask":
        assert pixels[..., 0].max() <= 1.0


def test_twin_is_finite_at_the_extremes():
    rng = np.random.default_rng(0)
    positions = (rng.standard_normal((20000, 3)) * 10.0 ** rng.uniform(-6, 6, (20000, 1))).astype(np.float32)
    n_dot_v = np.concatenate([[0.0, 1.0], rng.uniform(0, 1, 19998)]).astype(np.float32)
    for size in (1e-6, 1e-3, 1.0, 1e6, 0.0):
        for power in (-5.0, 0.0, 1.0, 1e6):
            for strength in (0.0, 1.0, 1e6):
                mask, color = twin.glints(positions, n_dot_v, 0.0, size, power, (1, 1, 1), strength, 7)
                assert np.isfinite(mask).all() and np.isfinite(color).all()
                assert mask.min() >= 0.0 and mask.max() <= 1.0
