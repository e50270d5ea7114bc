"""What makes the layer read as cumulus, measured on its twin (core.clouds, which the grid and the
procedural density match; tests/test_cloud_grid.py, tests/test_cloud_twins.py): outlines as
fractal as real clouds' seen from below, rough seen from the side, and flat bases.
"""

import math

import numpy as np

from core import clouds as twin
from core import outlines

OPAQUE = math.log(2.0)  # T < 0.5: what the coverage calibration counts as under cloud
LAYER = {"base": 1500.0, "thickness": 2500.0, "coverage": 0.4, "map_scale": 3000.0, "shape_scale": 1200.0,
         "detail_scale": 200.0, "erosion": 0.35, "curl": 0.5, "skew": 300.0, "density": 0.02,
         "precipitation": 0.0, "cloud_type": 0.5, "wind": (3.0, 1.0, 0.0), "time": 0.0}
SEEDS = (0, 7)


def side_views():
    """T < 0.5 seen from the side through 600 m of sky, 25 m pixels, two seeds, two places."""
    return [twin.optical_depth_side({**LAYER, "seed": seed}, (x, 0.0), 8000.0, 600.0, 320, 10) > OPAQUE
            for seed in SEEDS for x in (0.0, 9000.0)]


def test_outlines_seen_from_below_are_as_fractal_as_real_clouds():
    """Lovejoy (1982): perimeter ~ area^(D/2) with D about 1.35 over many clouds; the issue asks
    1.25 to 1.5. Smooth outlines give 1.0 (discs: 1.01, below)."""
    masks = [twin.optical_depth_up({**LAYER, "seed": seed}, (0.0, 0.0), 24000.0, 200, 10) > OPAQUE
             for seed in SEEDS]
    dimension, clouds = outlines.dimension(masks)
    print(f"from below: D {dimension:.3f} over {clouds} clouds")
    assert clouds >= 30
    assert 1.25 <= dimension <= 1.5


def test_area_perimeter_gives_one_for_smooth_shapes():
    rows, cols = np.mgrid[:300, :300]
    discs = [(cols - 150) ** 2 + (rows - 150) ** 2 < r * r for r in (5, 10, 20, 40, 80, 120)]
    dimension, count = outlines.dimension(discs)
    assert count == 6 and abs(dimension - 1.0) < 0.03


def test_side_outlines_are_rough_and_bases_flat():
    """From the side the flat base is a straight line by design, so D is lower than from below;
    still above smooth shapes'. Bases: across every cloudy column of the side views, the lowest
    opaque point lies within a tenth of the layer's thickness of the base for 90 % of them."""
    views = side_views()
    dimension, clouds = outlines.dimension(views, min_area=8)
    rows = views[0].shape[0]
    bases = []
    for view in views:
        cloudy = view.any(axis=0)
        lowest = np.argmax(view, axis=0)[cloudy]  # rows run up from the base
        bases.append((lowest + 0.5) / rows)
    bases = np.concatenate(bases)
    print(f"from the side: D {dimension:.3f} over {clouds} clouds; base heights (share of the thickness) "
          f"10th / 50th / 90th percentile {np.percentile(bases, [10, 50, 90]).round(3)}")
    assert clouds >= 10 and dimension >= 1.1
    assert np.percentile(bases, 90) <= 0.1
