"""Node group Sandscape Footprint Height against its numpy twin, baked at texel centres.

A random print map (R, G and B anywhere in 0..1) goes through an Image Texture (Closest)
on a UV plane with one bake pixel per texel; Height is baked through an emission.
"""

import bpy
import numpy as np
import pytest

from core import footprints as twin
from devtools import readback

RES = 32
GAIN, OFFSET = 10.0, 0.5  # emission = height * GAIN + OFFSET keeps negative heights visible
TOLERANCE = 1e-6  # metres


@pytest.fixture
def print_map():
    rng = np.random.default_rng(7)
    pixels = rng.random((RES, RES, 4)).astype(np.float32)
    pixels[::3, ::3, :2] = 0.0  # untouched sand
    image = bpy.data.images.new("Print Map", RES, RES, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    image.alpha_mode = "CHANNEL_PACKED"
    image.pixels.foreach_set(pixels.ravel())
    return image, pixels


def probe_material(sandscape, image, values, output="Height"):
    helper = sandscape.node_groups.helper
    group = helper.ensure_group(sandscape.node_groups.footprint_height)
    material = bpy.data.materials.new("Footprint Probe")
    tree = material.node_tree
    tree.nodes.clear()
    texture = helper.add_node(tree, "ShaderNodeTexImage", image=image, interpolation="Closest")
    node = helper.add_node(tree, "ShaderNodeGroup", node_tree=group)
    helper.link(tree, texture.outputs["Color"], node.inputs["Print Map"])
    coordinates = helper.add_node(tree, "ShaderNodeTexCoord")
    helper.link(tree, coordinates.outputs["Object"], node.inputs["Vector"])
    for key, value in values.items():
        node.inputs[key].default_value = value
    scaled = helper.add_node(tree, "ShaderNodeMath", operation="MULTIPLY_ADD", inputs={1: GAIN, 2: OFFSET})
    helper.link(tree, node.outputs[output], scaled.inputs[0])
    emission = helper.add_node(tree, "ShaderNodeEmission", inputs={"Strength": 1.0})
    helper.link(tree, scaled.outputs[0], emission.inputs["Color"])
    output = helper.add_node(tree, "ShaderNodeOutputMaterial")
    helper.link(tree, emission.outputs[0], output.inputs["Surface"])
    return material


@pytest.mark.parametrize("depth, frame, refill", [(0.03, 100.0, 0.0), (0.03, 200.0, 40.0), (0.0, 100.0, 0.0)])
def test_pressed_matches_the_twin(sandscape, print_map, depth, frame, refill):
    """Pressed, the ripples' Flatten: R where the texel is born, eased by the refill, whatever the
    rim or the depth's size; none at Depth 0 (the prints turned off)."""
    image, pixels = print_map
    values = {"Depth": depth, "Rim": 0.008, "Frame": frame, "Frame Start": 1.0, "Frame End": 250.0,
              "Noise Amount": 0.15, "Refill Time": refill}
    material = probe_material(sandscape, image, values, "Pressed")
    plane = readback.uv_plane()
    plane.data.materials.append(material)
    baked = (readback.bake_emit(plane, material, RES)[..., 0] - OFFSET) / GAIN
    expected = twin.revealed_pressed(pixels, depth, frame, (1.0, 250.0), refill=refill)
    assert np.abs(baked - expected).max() < TOLERANCE * 10  # a share, not metres: 1e-5
    born = pixels[..., 2] * 249.0 + 1.0 < frame
    assert np.array_equal(expected > 0, born & (pixels[..., 0] > 0) & (depth > 0))
    assert 0.3 < born.mean() < 0.9 and expected.max() <= 1.0


@pytest.mark.parametrize("depth, rim, frame, start, end, refill", [
    (0.03, 0.008, 100.0, 1.0, 250.0, 0.0),
    (0.03, 0.008, 1.0, 1.0, 250.0, 0.0),
    (0.5, 0.0, 37.0, 10.0, 60.0, 0.0),
    (0.01, 0.2, 61.0, 10.0, 60.0, 0.0),
    (0.03, 0.008, 5.0, 5.0, 5.0, 0.0),  # a one-frame range
    (0.03, 0.008, 200.0, 1.0, 250.0, 40.0),  # the wind filling the prints in
])
def test_height_matches_the_twin(sandscape, print_map, depth, rim, frame, start, end, refill):
    image, pixels = print_map
    values = {"Depth": depth, "Rim": rim, "Frame": frame, "Frame Start": start, "Frame End": end,
              "Noise Amount": 0.0, "Refill Time": refill}
    material = probe_material(sandscape, image, values)
    plane = readback.uv_plane()
    plane.data.materials.append(material)
    baked = (readback.bake_emit(plane, material, RES)[..., 0] - OFFSET) / GAIN
    expected = twin.revealed_height(pixels, depth, rim, frame, (start, end), refill=refill)
    assert np.abs(baked - expected).max() < TOLERANCE
    if refill:  # the law itself, not the twin: what is left of a print is exp(-age / refill)
        birth = pixels[..., 2] * (end - start) + start
        pressed = pixels[..., 1] * rim - pixels[..., 0] * depth
        law = np.where(birth < frame, pressed * np.exp(-(frame - birth) / refill), 0.0)
        assert np.abs(baked - law).max() < 2 * TOLERANCE
        assert np.abs(law).max() > 1e-3 and (np.abs(law) < 0.5 * np.abs(pressed)).mean() > 0.3
    shown = (expected != 0).mean()
    if start < frame < end:  # part of the map is born, part is not: the birth test is exercised
        assert 0.1 < shown < 0.9


def test_noise_varies_height_within_its_amount(sandscape, print_map):
    image, pixels = print_map
    values = {"Depth": 0.03, "Rim": 0.008, "Frame": 300.0, "Frame Start": 1.0, "Frame End": 250.0,
              "Noise Amount": 0.2, "Noise Scale": 3.0}
    material = probe_material(sandscape, image, values)
    plane = readback.uv_plane()
    plane.data.materials.append(material)
    baked = (readback.bake_emit(plane, material, RES)[..., 0] - OFFSET) / GAIN
    base = twin.revealed_height(pixels, 0.03, 0.008, 300.0, (1.0, 250.0))
    ratio = baked[base != 0] / base[base != 0]
    assert ratio.min() >= 0.8 - 1e-4 and ratio.max() <= 1.2 + 1e-4 and ratio.std() > 0.01


@pytest.mark.parametrize("wind", [(-3.0, 0.0, 0.0), (3.0, 0.0, 0.0), (0.0, 0.0, 0.0)],
                         ids=["windward", "lee", "calm"])
def test_the_wind_fills_prints_on_a_windward_slope_faster(sandscape, print_map, wind):
    """On a plane tilted 20 degrees to face +X: a wind from +X (blowing along -X) fills its prints
    (1 + 2 tan 20)^3 times faster; blowing along +X (the lee) or calm, at the flat rate. Checked
    against the twin and against the law exp(-age rate / refill)."""
    image, pixels = print_map
    values = {"Depth": 0.03, "Rim": 0.008, "Frame": 200.0, "Frame Start": 1.0, "Frame End": 250.0,
              "Noise Amount": 0.0, "Refill Time": 200.0, "Wind": wind}
    material = probe_material(sandscape, image, values)
    plane = readback.uv_plane()
    plane.rotation_euler.y = np.radians(20.0)
    plane.data.materials.append(material)
    baked = (readback.bake_emit(plane, material, RES)[..., 0] - OFFSET) / GAIN
    normal = (np.sin(np.radians(20.0)), 0.0, np.cos(np.radians(20.0)))
    expected = twin.revealed_height(pixels, 0.03, 0.008, 200.0, (1.0, 250.0), refill=200.0, normal=normal,
                                    wind=wind)
    assert np.abs(baked - expected).max() < TOLERANCE
    rate = (1 + 2 * np.tan(np.radians(20.0))) ** 3 if wind[0] < 0 else 1.0
    birth = pixels[..., 2] * 249.0 + 1.0
    pressed = pixels[..., 1] * 0.008 - pixels[..., 0] * 0.03
    law = np.where(birth < 200.0, pressed * np.exp(-(200.0 - birth) * rate / 200.0), 0.0)
    assert np.abs(baked - law).max() < 2 * TOLERANCE
