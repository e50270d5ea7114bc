"""Numerical stability sweep over every core/ function: at least 10,000 seeded cases each,
spanning zero, tiny, huge and negative values, and no NaN or Inf in any result.

Inputs are finite (the operators refuse NaN before it reaches core/). Where a function's
domain is narrower (wavelengths > 0, |g| < 1, decay <= 1), the sweep stays inside it and the
refusal of the rest is tested beside the function.
"""

import numpy as np
import pytest

from core import (
    atmosphere,
    dune_field,
    dune_horizon,
    dune_surface,
    dunes,
    footprints,
    glints,
    noise_hash,
    paths,
    post,
)
from core import sole as soles

CASES = 10_000
RNG_SEED = 20261122


def extreme(rng, n, low=-12, high=12, signed=True, zeros=True):
    """Log-uniform magnitudes 10^low..10^high, random signs, and some exact zeros and ones."""
    values = 10.0 ** rng.uniform(low, high, n)
    if signed:
        values *= rng.choice([-1.0, 1.0], n)
    if zeros:
        values[rng.random(n) < 0.05] = 0.0
        values[rng.random(n) < 0.05] = 1.0
    return values


@pytest.fixture
def rng():
    return np.random.default_rng(RNG_SEED)


def finite(*arrays):
    return all(np.isfinite(np.asarray(a, dtype=np.float64)).all() for a in arrays)


def test_noise_hash(rng):
    keys = rng.integers(0, 2**32, size=(4, CASES), dtype=np.uint64).astype(np.uint32)
    assert noise_hash.hash_uint3(*keys[:3]).dtype == np.uint32
    unit = noise_hash.uint_to_unit(noise_hash.hash_uint4(*keys))
    assert finite(unit) and unit.min() >= 0 and unit.max() <= 1
    positions = np.stack([extreme(rng, CASES, -30, 30) for _ in range(3)], -1).astype(np.float32)
    for noise in (noise_hash.white_noise_3d(positions),
                  noise_hash.white_noise_4d(positions, np.float32(extreme(rng, 1)[0]))):
        assert finite(noise) and noise.min() >= 0 and noise.max() <= 1


def test_glints(rng):
    positions = np.stack([extreme(rng, CASES, -6, 6) for _ in range(3)], -1)
    n_dot_v = rng.uniform(0, 1, CASES)
    for size, power, strength in ((1e-6, 0.0, 1e6), (1e6, 256.0, 1e-6), (0.0, -5.0, 1.0), (0.01, 8.0, 30.0)):
        seed = int(rng.integers(0, 2**24))
        mask, color = glints.glints(positions, n_dot_v, rng.uniform(0, 1), size, power, (1, 1, 1, 1),
                                    strength, seed)
        assert finite(mask, color) and mask.min() >= 0 and mask.max() <= 1
    image = glints.noise_image(64, 3)
    uv = np.stack([extreme(rng, CASES, -6, 6), extreme(rng, CASES, -6, 6)], -1)
    assert finite(glints.sample_nearest(image, uv))


def test_paths(rng):
    for _ in range(CASES // 500):
        count = int(rng.integers(3, 60))
        scale = 10.0 ** rng.uniform(-4, 4)
        positions = np.cumsum(rng.normal(0, scale, (count, 3)), axis=0)
        frames = np.arange(count, dtype=float)
        stride = scale * 10.0 ** rng.uniform(-1.5, 1.5)
        steps = paths.plan_steps(positions, frames, stride, scale * rng.uniform(0, 1))
        assert all(finite(v) for v in steps.values())
        assert np.allclose(np.linalg.norm(steps["forward"], axis=1), 1.0)
    normals = np.stack([extreme(rng, CASES, -6, 6) for _ in range(3)], -1)
    normals[:, 2] = np.abs(normals[:, 2]) + 1e-3  # facing up, however steep
    headings = rng.uniform(-np.pi, np.pi, CASES)
    forward = np.stack([np.cos(headings), np.sin(headings), 0 * headings], -1)
    tangent, lateral = paths.surface_frames(forward, normals)
    assert finite(tangent, lateral)


def test_footprint_painter(rng):
    sole = soles.Sole()
    distance = extreme(rng, CASES, -9, 9)
    pressed, rim = soles.sole_profile(distance, sole, 10.0 ** rng.uniform(-6, 2))
    assert finite(pressed, rim) and pressed.min() >= 0 and pressed.max() <= 1 and rim.max() <= 1
    a, b = extreme(rng, CASES, -9, 9), extreme(rng, CASES, -9, 9)
    assert finite(soles.sole_distance(a, b, sole))
    # 10,000 prints of every size of scale, heading and birth, into one small map.
    centres = rng.normal(0, 2, (CASES, 2))
    angle = rng.uniform(0, 2 * np.pi, CASES)
    tilt = rng.uniform(0.05, 1, CASES)[:, None]  # projected axes shortened by a steep slope
    forward = np.stack([np.cos(angle), np.sin(angle)], -1) * tilt
    lateral = np.stack([-np.sin(angle), np.cos(angle)], -1)
    births = extreme(rng, CASES, -6, 6)
    scales = 10.0 ** rng.uniform(-6, 3, CASES)
    region = footprints.fit_region(centres, sole.reach(), 256, 0.1)
    image = footprints.paint(centres, forward, lateral, births, scales, region, sole, (-1e6, 1e6))
    assert finite(image) and image[..., 0].max() <= scales.max() * (1 + 1e-6)
    for frame in extreme(rng, 8, -6, 6):
        assert finite(footprints.revealed_height(image, 1e3, 1e3, frame, (-1e6, 1e6)))
    faces = np.stack([extreme(rng, CASES, -6, 6) for _ in range(3)], -1)
    assert footprints.faces_in_region(faces, (-1, -1), (1, 1)).dtype == bool


def test_atmosphere(rng):
    cosines = rng.uniform(-1, 1, CASES)
    assert finite(atmosphere.rayleigh_phase(cosines))
    for g in (-0.999, -0.5, 0.0, 0.5, 0.999):
        assert finite(atmosphere.henyey_greenstein(cosines, g))
    wavelengths = 10.0 ** rng.uniform(0, 5, (CASES, 3))  # 1 nm to 0.1 mm
    densities = 10.0 ** rng.uniform(-12, 6, CASES)
    beta = np.array([atmosphere.rayleigh_coefficients(d, w)
                     for d, w in zip(densities, wavelengths, strict=True)])
    assert finite(beta) and (beta >= 0).all()
    tau = np.abs(extreme(rng, CASES, -12, 12))
    t = atmosphere.transmittance(tau)
    assert finite(t) and t.min() >= 0 and t.max() <= 1
    assert finite(atmosphere.sun_direction(rng.uniform(-np.pi, np.pi, CASES), rng.uniform(-10, 10, CASES)))


def test_post(rng):
    channels = [extreme(rng, CASES, -12, 6, zeros=True) for _ in range(4)]
    image = np.abs(np.stack(channels, -1)).reshape(100, 100, 4)
    for threshold in (0.0, 1e-9, 1e9):
        assert finite(post.gated_blur(image, threshold))
    u, v = extreme(rng, CASES, -6, 6), extreme(rng, CASES, -6, 6)
    assert finite(post.sample_bilinear(image, u, v))
    sun = (rng.uniform(-3, 3), rng.uniform(-3, 3))
    rays = post.god_rays(image[:32, :32, :3], sun, 16, 1.0, 1.0, 1.0, 1e3)
    assert finite(rays)
    for _ in range(CASES // 10):
        matrix = rng.normal(0, 10.0 ** rng.uniform(-3, 3), (4, 4))
        uv, in_front = post.screen_position(matrix, rng.normal(0, 1, 3))
        intensity = post.sun_intensity(uv, in_front, rng.uniform(0, 1))
        assert 0.0 <= intensity <= 1.0 and (finite(uv) or not in_front)


def test_dunes(rng):
    """The dune field at extreme points, sizes and winds: every height finite, every lattice
    within its limits (the operator's limits bound the inputs)."""
    field = dune_field.grow((32, 32), 4.0, 1, steps=5)
    surface = dune_surface.surface_from_slabs(field.slabs, 0.5, float(rng.uniform(-10, 10)))
    x, y = extreme(rng, CASES, -3, 7), extreme(rng, CASES, -3, 7)
    blur = np.abs(extreme(rng, CASES, -3, 7))
    assert finite(surface.heights(x, y, blur))
    for _ in range(CASES):
        width, depth = 10.0 ** rng.uniform(-2, 6, 2)
        cell = 10.0 ** rng.uniform(-3, min(4, np.log10(min(width, depth))))
        spacing = max(4 * cell, 10.0 ** rng.uniform(-2, 5))
        coarse, coarse_cell, refinements = dunes.plan(width, depth, cell, spacing)
        assert 64 <= coarse <= dunes.COARSE_LIMIT and coarse * 2**refinements <= dunes.FINE_LIMIT
        assert np.isfinite(coarse_cell) and coarse_cell > 0
    supplies = rng.uniform(0.05, 30.0, CASES)
    assert finite(dunes.supply_slabs(supplies)) and (dunes.supply_slabs(supplies) > 0).all()
    for angle, share in zip(extreme(rng, CASES // 10, -6, 2), rng.uniform(0, 1, CASES // 10), strict=True):
        blowing, frame = dunes.winds(angle, share)
        assert np.isfinite(frame) and all(abs(np.hypot(*d) - 1) < 1e-9 for d, _ in blowing)


def test_dune_meshes(rng):
    """Slope limiting and the horizon's loops on random and degenerate triangles: finite, never
    raised, loops always joined."""
    for _ in range(CASES // 1000):
        vertices = np.c_[rng.uniform(-1, 1, (500, 2)) * 10.0 ** rng.uniform(-3, 3), extreme(rng, 500, -6, 6)]
        vertices[rng.random(500) < 0.05, :2] = 0.0  # coincident points: zero-area triangles
        triangles = rng.integers(0, 500, (1000, 3))
        before = vertices[:, 2].copy()
        dune_surface.limit_triangle_slopes(vertices, triangles, float(rng.uniform(1, 89)), max_rounds=50)
        assert finite(vertices) and (vertices[:, 2] <= before).all()
    for _ in range(CASES // 10):
        offsets = dune_horizon.loop_offsets(10.0 ** rng.uniform(-3, 3), 10.0 ** rng.uniform(-1, 6))
        assert finite(offsets) and len(offsets) < 2000
        n, m = rng.integers(4, 60, 2)
        inner = np.sort(rng.uniform(0, 4, n))
        outer = np.sort(rng.uniform(0, 4, m))
        triangles = dune_horizon.zip_loops(np.arange(n), inner, n + np.arange(m), outer)
        assert len(triangles) == n + m and triangles.min() >= 0 and triangles.max() < n + m
