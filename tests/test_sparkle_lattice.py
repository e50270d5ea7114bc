"""No lattice of specks: where nearly every coarse cell glints (small grains far off, a shaded slope
mirroring the sky), sparkles at the lattice points beat with the pixels into a regular pattern (the
twelfth review saw specks about 7 px apart on the poster's shaded slopes). Jittered in their cells
they scatter: the power spectrum of the twin's mirror share has no peak standing out. The group is
its twin pixel for pixel (tests/test_glint_splat.py), so the twin carries the check.
"""

import math

import numpy as np
import pytest

from core import glint_splat as twin

WIDTH, HEIGHT, FOCAL = 160, 90, 50.0 / 36.0 * 160  # pixels; a 50 mm lens on a 36 mm sensor
EYE, PITCH = np.array([0.0, -30.0, 1.6]), math.radians(80)  # eye height over flat sand
GRAIN, THRESHOLD = 0.002, 0.985
PEAK_LIMIT = 30.0  # highest bin over the median: white noise gives 14-16, the lattice points 64


def eye_height_shares():
    """The twin's mirror share per pixel of flat sand (z = 0) below the horizon, rows from the top."""
    cos, sin = math.cos(PITCH), math.sin(PITCH)
    turn = np.array([[1, 0, 0], [0, cos, -sin], [0, sin, cos]])

    def hit(columns, rows):
        across, up = (columns - WIDTH / 2) / FOCAL, (HEIGHT / 2 - rows) / FOCAL
        ray = np.stack([across, up, -np.ones_like(columns)], -1)
        ray = ray @ turn.T
        return EYE + (-EYE[2] / ray[..., 2])[..., None] * ray

    def project(points):
        seen = (points - EYE) @ turn
        depth = -seen[..., 2]
        return WIDTH / 2 + FOCAL * seen[..., 0] / depth, HEIGHT / 2 - FOCAL * seen[..., 1] / depth

    rows, columns = np.mgrid[HEIGHT - 64:HEIGHT, 0:WIDTH] + 0.5  # the lowest 64 rows: all sand
    centres = hit(columns, rows)
    step_u = hit(columns + 0.5, rows) - hit(columns - 0.5, rows)
    step_v = hit(columns, rows + 0.5) - hit(columns, rows - 0.5)
    normals = np.broadcast_to([0.0, 0.0, 1.0], centres.shape)

    def project_rows(points):  # the twin's rows count up from the first row taken
        u, v = project(points)
        return u, v - (HEIGHT - 64)

    return twin.pixel_amounts(centres, step_u, step_v, normals, project_rows, GRAIN, THRESHOLD, 0.0)


def spectrum_peak(shares):
    """The highest bin of the mean-free power spectrum over its median."""
    power = np.abs(np.fft.rfft2(shares - shares.mean())) ** 2
    power[0, 0] = 0.0
    return float(power.max() / np.median(power))


@pytest.mark.parametrize("jitter", [twin.JITTER, 0.0])
def test_sparkles_scatter_rather_than_line_up(monkeypatch, jitter):
    monkeypatch.setattr(twin, "JITTER", jitter)
    monkeypatch.setattr(twin, "CELL_REACH", 2.0 * twin.TENT_REACH / (2.0 - jitter) if jitter else 1.0)
    shares = eye_height_shares()
    peak = spectrum_peak(shares)
    print(f"jitter {jitter}: mirror share {shares.mean():.4f}, spectrum peak {peak:.1f} x the median")
    assert shares.mean() > 0.01  # sparkles in view
    if jitter:
        assert peak <= PEAK_LIMIT
    else:  # the lattice points themselves: the check can fail
        assert peak > PEAK_LIMIT
