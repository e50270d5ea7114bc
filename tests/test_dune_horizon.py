"""The land beyond the field: draa (megadunes) swell its far loops into crests across the wind,
so the horizon is not a straight line; near the field the ring stays the field's own dunes."""

import math

import numpy as np
import pytest

from core import dune_horizon
from core.dune_surface import DuneSurface


def ridged_surface(wind_angle, relief=6.0, cell=0.5, cells=240):
    """A periodic field of ridges across the wind, `relief` metres crest to trough."""
    along = np.arange(cells) * cell
    z = 0.5 * relief * (1.0 + np.sin(2 * math.pi * along / 30.0))
    return DuneSurface(np.tile(z, (cells, 1)), cell, wind_angle)


@pytest.mark.parametrize("wind", [0.0, 0.7])
def test_draa_rise_beyond_the_field_across_the_wind(wind):
    surface = ridged_surface(wind)
    width = depth = 120.0
    count = int(width / 0.5)
    boundary = dune_horizon.boundary_indices(count, count)
    gx, gy = np.meshgrid(np.arange(count + 1) * 0.5 - 60.0, np.arange(count + 1) * 0.5 - 60.0)
    corners = np.stack([gx.ravel(), gy.ravel(), surface.heights(gx.ravel(), gy.ravel())])
    vertices, _ = dune_horizon.ring(surface, width, depth, 0.5, 4000.0, corners[:, boundary])
    offset = np.maximum(np.abs(vertices[:, 0]) - 60.0, np.abs(vertices[:, 1]) - 60.0)
    land = vertices[:, 2] + offset**2 / (2 * dune_horizon.EARTH_RADIUS_M)  # the Earth's curve back out
    added = land - surface.heights(vertices[:, 0], vertices[:, 1], blur=0.0)
    near = offset <= dune_horizon.DRAA_START_M
    far = offset >= dune_horizon.DRAA_FULL_M
    # Near the field nothing is added (the blur of the coarse loops aside: within the field's relief).
    assert np.abs(added[near]).max() <= 6.0 + 1e-9
    assert near.sum() > 100
    assert (dune_horizon.draa(vertices[near, 0], vertices[near, 1], offset[near], wind, 6.0) == 0).all()
    expected = dune_horizon.draa(vertices[far, 0], vertices[far, 1], offset[far], wind, 6.0)
    blurred = land[far] - expected  # what the far loops keep of the field: between trough and crest
    assert blurred.min() >= -1e-6 and blurred.max() <= 6.0 + 1e-6
    # Full height: crests DRAA_RELIEF times the field's relief, troughs at none.
    assert expected.max() == pytest.approx(dune_horizon.DRAA_RELIEF * 6.0, rel=0.01)
    assert expected.min() == pytest.approx(0.0, abs=0.05 * dune_horizon.DRAA_RELIEF * 6.0)
    # The crests run across the wind: along it the draa rise and fall the whole way (to the
    # saddles' height at least); across it only the saddles and the wander change them.
    downwind = np.array([math.cos(wind), math.sin(wind)])
    across = np.array([-downwind[1], downwind[0]])
    spot = 2500.0 * across + 300.0 * downwind
    steps = np.linspace(0.0, dune_horizon.DRAA_SPACING_M, 50)

    def profile(direction):
        points = spot + steps[:, None] * direction
        return dune_horizon.draa(points[:, 0], points[:, 1], 2000.0, wind, 6.0)
    full = dune_horizon.DRAA_RELIEF * 6.0
    assert np.ptp(profile(downwind)) > 0.95 * (1 - dune_horizon.DRAA_SADDLE) * full
    assert np.ptp(profile(across)) < 0.8 * full


def test_flat_land_grows_no_draa():
    relief = np.ptp(DuneSurface(np.zeros((8, 8)), 1.0, 0.0).levels[0])
    assert np.all(dune_horizon.draa(np.array([3000.0]), np.array([10.0]), 3000.0, 0.0, relief) == 0)
