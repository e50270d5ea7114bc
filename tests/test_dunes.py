"""The dune height field: finite, slip faces within the angle of repose, gentle windward slopes."""

import numpy as np

from core import dunes


def test_slopes_respect_sand_physics():
    x, y = np.meshgrid(np.arange(-40, 40, 0.02), np.arange(-20, 20, 0.5))
    z = dunes.dune_heights(x, y, ripple_height=0.0)
    assert np.isfinite(z).all()
    slope_along = np.degrees(np.arctan(np.diff(z, axis=1) / 0.02))
    # A slope of the meandering crest line adds a little; the plain profile stays under repose.
    assert dunes.max_lee_slope_degrees() < dunes.REPOSE_DEGREES
    assert -slope_along.max() < 45 and (-slope_along).max() > 15  # a steep lee exists, not a cliff
    assert np.percentile(np.abs(slope_along), 50) < 15  # most of the ground is gentle


def test_heights_stay_within_their_amplitude():
    x, y = np.meshgrid(np.linspace(-50, 50, 401), np.linspace(-50, 50, 401))
    z = dunes.dune_heights(x, y, height=2.0, ripple_height=0.03)
    assert z.min() >= -0.03 - 1e-9 and z.max() <= 2.0 + 0.03 + 1e-9


def test_grid_shape():
    vertices, quads = dunes.grid(10.0, 6.0, 0.5)
    assert vertices.shape == (21 * 13, 3) and quads.shape == (20 * 12, 4)
    assert quads.max() == len(vertices) - 1
