"""Glint statistics through Blender's own hash (bakes), and the twin over a million cells."""

import math
from collections import deque

import numpy as np
import pytest

from core import glints as twin
from devtools import readback, scenes

PLANE = 2.0


def bake_mask(group, threshold, size, res, seed=0):
    obj = readback.uv_plane(PLANE)
    material = scenes.group_material(group, {"Threshold": threshold, "Glint Size": size,
                                             "Facing Power": 0.0, "Seed": float(seed)}, "Mask")
    obj.data.materials.append(material)
    return readback.bake_emit(obj, material, res)[..., 0] > 0.5


def component_areas(mask):
    """Pixel counts of the 4-connected lit regions (a glint made of touching cells is one)."""
    seen = np.zeros_like(mask, dtype=bool)
    areas = []
    height, width = mask.shape
    for start in zip(*np.nonzero(mask), strict=True):
        if seen[start]:
            continue
        seen[start] = True
        queue, area = deque([start]), 0
        while queue:
            y, x = queue.popleft()
            area += 1
            for ny, nx in ((y + 1, x), (y - 1, x), (y, x + 1), (y, x - 1)):
                if 0 <= ny < height and 0 <= nx < width and mask[ny, nx] and not seen[ny, nx]:
                    seen[ny, nx] = True
                    queue.append((ny, nx))
        areas.append(area)
    return np.array(areas)


def test_component_areas_counts_regions():
    mask = np.zeros((6, 6), bool)
    mask[0:2, 0:2] = True
    mask[4, 4] = mask[4, 5] = mask[5, 5] = True
    assert sorted(component_areas(mask)) == [3, 4]


@pytest.mark.parametrize("threshold", [0.1, 0.5, 0.9, 0.99])
def test_lit_cell_fraction_is_one_minus_threshold(glints_group, threshold):
    """256² bake, cells of 2 px: one pixel per cell gives 16384 independent cells."""
    res, size = 256, PLANE / 128
    per_cell = bake_mask(glints_group, threshold, size, res)[1::2, 1::2]
    p = 1.0 - threshold
    sigma = math.sqrt(p * (1 - p) / per_cell.size)
    assert abs(per_cell.mean() - p) <= 3 * sigma


def test_mean_glint_area_scales_with_size_squared(glints_group):
    """Sizes of 2, 4 and 8 px on a 512² bake: mean glint area / size² stays the same."""
    res = 512
    pixel = PLANE / res
    normalised = []
    for cells in (2, 4, 8):
        areas = component_areas(bake_mask(glints_group, 0.9, cells * pixel, res, seed=cells))
        assert len(areas) > 300
        normalised.append(areas.mean() / cells**2)
    # Scale-free: each is near 1 cell per glint (plus the odd touching neighbour).
    assert max(normalised) / min(normalised) < 1.15, normalised
    assert all(1.0 <= n < 1.5 for n in normalised), normalised


def test_twin_fraction_over_a_million_cells():
    cells = np.stack(np.meshgrid(np.arange(1000), np.arange(1000), [0.0]), -1).reshape(-1, 3)
    for threshold in (0.0, 0.25, 0.5, 0.75, 0.95, 0.999):
        noise = twin.cell_noise(cells.astype(np.float32), 1.0, seed=42)
        p = 1 - threshold
        sigma = math.sqrt(max(p * (1 - p), 1e-12) / noise.size)
        assert abs((noise > threshold).mean() - p) <= 3 * sigma + 1e-12


def test_seeds_give_independent_patterns():
    cells = np.stack(np.meshgrid(np.arange(300), np.arange(300), [0.0]), -1).reshape(-1, 3)
    a = twin.cell_noise(cells.astype(np.float32), 1.0, seed=1) > 0.5
    b = twin.cell_noise(cells.astype(np.float32), 1.0, seed=2) > 0.5
    agreement = (a == b).mean()
    assert abs(agreement - 0.5) < 0.01
