"""The glint groups against their numpy twins, baked at pixel centres (1 sample).

An EMIT bake views along the normal, so Layer Weight Facing is 0 and N·V = 1 there:
the facing term is checked by rendering (test_glints_render.py).
"""

import bpy
import numpy as np
import pytest

from core import glints as twin
from devtools import readback, scenes

RES = 128
PLANE = 2.0  # metres: one pixel is 1/64 m
BAKE_TOLERANCE = 1e-5

# (threshold, size, power, seed, strength). Cells are centred on multiples of the size, so
# sizes of an even number of pixels keep every cell edge on a pixel edge, half a pixel from
# any bake point.
PARAMETER_SETS = [
    (0.0, 1 / 16, 8.0, 0, 1.0),
    (1.0, 1 / 16, 8.0, 3, 1.0),
    (0.5, 1 / 32, 2.0, 7, 2.5),
    (0.9, 1 / 32, 1.0, 11, 1.0),
    (0.97, 1 / 8, 0.0, 123, 30.0),
    (0.3, 0.25, 100.0, 5, 1e6),
]


def plane_positions(res=RES, size=PLANE):
    c = readback.pixel_centres(res, -size / 2, size / 2)
    x, y = np.meshgrid(c, c)
    return np.stack([x, y, np.zeros_like(x)], axis=-1)


def glint_values(threshold, size, power, seed, strength, color=(1.0, 1.0, 1.0, 1.0)):
    return {"Threshold": threshold, "Glint Size": size, "Facing Power": power,
            "Seed": float(seed), "Strength": strength, "Color": color}


@pytest.fixture
def plane():
    return readback.uv_plane(PLANE)


def bake_group_output(group, obj, values, output):
    material = scenes.group_material(group, values, output)
    obj.data.materials.clear()
    obj.data.materials.append(material)
    return readback.bake_emit(obj, material, RES)


@pytest.mark.parametrize("threshold,size,power,seed,strength", PARAMETER_SETS)
def test_mask_bake_equals_twin(glints_group, plane, threshold, size, power, seed, strength):
    values = glint_values(threshold, size, power, seed, strength)
    baked = bake_group_output(glints_group, plane, values, "Mask")[..., 0]
    expected, _ = twin.glints(plane_positions(), 1.0, threshold, size, power, (1, 1, 1), strength, seed)
    assert np.abs(baked - expected).max() <= BAKE_TOLERANCE
    if threshold == 0.0:
        assert expected.min() == 1.0
    if threshold == 1.0:
        assert expected.max() == 0.0


def test_glint_color_bake_equals_twin(glints_group, plane):
    values = glint_values(0.6, 1 / 32, 4.0, 9, 7.0, color=(1.0, 0.5, 0.25, 1.0))
    baked = bake_group_output(glints_group, plane, values, "Glint Color")[..., :3]
    _, expected = twin.glints(plane_positions(), 1.0, 0.6, 1 / 32, 4.0, (1.0, 0.5, 0.25), 7.0, 9)
    assert np.abs(baked - expected).max() <= BAKE_TOLERANCE * 7.0
    assert 0.2 < (expected[..., 0] > 0).mean() < 0.6  # the comparison covered lit and unlit cells


def test_unaligned_size_matches_away_from_cell_edges(glints_group, plane):
    """A size in real units (3 mm); bake points closer than 1e-5 cell to an edge are left out."""
    size = 0.003 * 5  # 1.5 cm: about one cell per pixel at this bake resolution
    baked = bake_group_output(glints_group, plane, glint_values(0.5, size, 1.0, 2, 1.0), "Mask")[..., 0]
    positions = plane_positions()
    expected, _ = twin.glints(positions, 1.0, 0.5, size, 1.0, (1, 1, 1), 1.0, 2)
    frac = positions[..., :2] / np.float32(size) + 0.5
    clear = np.all(np.abs(frac - np.round(frac)) > 1e-5, axis=-1)
    assert clear.mean() > 0.99
    assert np.abs(baked - expected)[clear].max() <= BAKE_TOLERANCE


def test_operator_material_emits_the_twin_glints(sandscape, plane):
    """The whole sand material: its EMIT bake is the glint colour (the BSDF does not emit)."""
    assert bpy.ops.sandscape.add_sand_material(
        glints="EMISSION", threshold=0.8, glint_size=1 / 16, facing_power=3.0,
        color=(1.0, 0.9, 0.7, 1.0),
        strength=12.0, seed=4) == {"FINISHED"}
    baked = readback.bake_emit(plane, plane.active_material, RES)[..., :3]
    _, expected = twin.glints(plane_positions(), 1.0, 0.8, 1 / 16, 3.0, (1.0, 0.9, 0.7), 12.0, 4)
    assert np.abs(baked - expected).max() <= BAKE_TOLERANCE * 12.0


def test_glints_follow_the_object_not_the_world(glints_group, plane):
    """Object-space cells: moving and turning the object leaves its glints where they were on it."""
    values = glint_values(0.5, 1 / 16, 1.0, 1, 1.0)
    still = bake_group_output(glints_group, plane, values, "Mask")[..., 0]
    plane.location = (3.2, -1.7, 0.4)
    plane.rotation_euler = (0.3, 0.2, 1.1)
    moved = readback.bake_emit(plane, plane.active_material, RES)[..., 0]
    # The mask is 0 or 1; another cell glinting would differ by 1. Bakes after a transform may
    # round differently (5.2 gives 1.0000001 where 5.0 gives 1.0).
    assert np.abs(still - moved).max() <= 1e-5


def test_image_source_bake_equals_twin(sandscape, plane):
    """Image source: a seeded 8-bit noise image, nearest texel through the UVs."""
    resolution, seed, threshold = 64, 17, 0.7
    assert bpy.ops.sandscape.add_sand_material(
        glints="EMISSION", source="IMAGE", image_resolution=resolution, seed=seed, threshold=threshold,
        facing_power=2.0, strength=1.0, color=(1.0, 1.0, 1.0, 1.0)) == {"FINISHED"}
    material = plane.active_material
    baked = readback.bake_emit(plane, material, RES)[..., 0]
    u = readback.pixel_centres(RES, 0.0, 1.0)
    uu, vv = np.meshgrid(u, u)
    noise = twin.sample_nearest(twin.noise_image(resolution, seed), np.stack([uu, vv], axis=-1))
    expected, _ = twin.glint_shade(noise, 1.0, threshold, 2.0, (1, 1, 1), 1.0)
    assert np.abs(baked - expected).max() <= BAKE_TOLERANCE
    image = sandscape.addon.sand.image_node(material).image
    assert image.packed_file is not None and image.colorspace_settings.name == "Non-Color"
