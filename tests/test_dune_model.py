"""The dune model (core/dune_field.py, core/dune_surface.py, core/dunes.py) on its physics:
slabs conserved, one seed one field, slip faces at the angle of repose and nowhere steeper,
gentle windward slopes, crests across the wind, barchans with horns downwind where sand is
scarce, and under two winds the crest trend Rubin and Hunter's (1987) rule predicts.

Reference figures (../shared/look-references.md): slip faces 30-34 degrees, windward slopes
about 5-15 degrees; dunes stand about a tenth of their spacing high.
"""

import math

import numpy as np
import pytest

from core import dune_field, dune_surface, dunes

WIND = math.radians(30.0)  # a diagonal wind: the lattice is laid along it, the mesh is not
SPACING = 24.0
BARE = 0.1  # metres: ground under less sand than this is bare (a sheet of strewn slabs at most)


def grown(supply, wind=WIND, seed=1, width=96.0, cell=0.5, spacing=SPACING):
    surface, facts = dunes.grow_surface(width, width, cell, spacing, supply, seed, wind)
    vertices, quads, _ = dunes.field_mesh(surface, width, width, cell)
    triangles = dune_surface.quad_triangles(quads)
    dune_surface.limit_triangle_slopes(vertices, triangles, 33.5)
    n = int(round(width / cell)) + 1
    return {"surface": surface, "facts": facts, "vertices": vertices, "triangles": triangles,
            "z": vertices[:, 2].reshape(n, n), "cell": cell, "wind": wind}


@pytest.fixture(scope="module")
def transverse():
    return grown(3.0)


@pytest.fixture(scope="module")
def barchans():
    return grown(0.8, wind=0.0, width=144.0)


def triangle_slopes(field):
    """Slope in degrees and along-wind component of each triangle's downhill direction."""
    v, t = field["vertices"], field["triangles"]
    normal = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    normal *= np.sign(normal[:, 2:3])
    slope = np.degrees(np.arctan2(np.hypot(normal[:, 0], normal[:, 1]), normal[:, 2]))
    wind = np.array([math.cos(field["wind"]), math.sin(field["wind"])])
    # The normal leans the way the ground falls: along the wind on a lee face.
    along = (normal[:, :2] @ wind) / np.maximum(np.hypot(normal[:, 0], normal[:, 1]), 1e-12)
    return slope, along


def test_slabs_are_only_moved():
    rng = np.random.default_rng(5)
    field = dune_field.SlabField(dune_field.initial_slabs((64, 64), 4.0, rng), 9)
    total = field.total()
    for direction in ((1.0, 0.0), (math.cos(2.1), math.sin(2.1))):
        for _ in range(40):
            field.sweep(np.array(direction))
            assert field.total() == total and field.slabs.min() >= 0
    field.refine()
    assert field.total() == 8 * total  # the same sand in slabs an eighth the volume


def test_avalanches_rest_at_repose_in_every_direction():
    rng = np.random.default_rng(2)
    h = rng.integers(0, 40, (48, 48)).astype(np.int32)
    total = h.sum()
    dune_field.avalanche(h)
    assert h.sum() == total and h.min() >= 0
    for (dy, dx), threshold in dune_field.AVALANCHE_EDGES:
        step = h - np.roll(h, (dy, dx), axis=(0, 1))
        assert np.abs(step).max() <= threshold
    assert abs(dune_field.repose_degrees() - 33.69) < 0.01  # atan(2/3): dry sand, 30-34 degrees


def test_avalanches_near_what_moved_move_what_full_passes_move():
    """The sparse passes (edges of the cells that moved) against full passes over every edge, on
    piles tall enough to slide down for dozens of rounds."""
    rng = np.random.default_rng(4)
    h = rng.integers(0, 4, (96, 96)).astype(np.int32)
    h[20:24, 30:34] += 300
    h[60, 70] += 500
    full, near = h.copy(), h.copy()
    rounds = dune_field.avalanche(full, sparse_below=0.0)
    assert dune_field.avalanche(near, sparse_below=1.0) == rounds > 30
    assert np.array_equal(full, near) and near.sum() == h.sum()


def test_shadow_matches_a_scan_of_every_upwind_cell():
    rng = np.random.default_rng(3)
    h = np.zeros((40, 64), np.int32)
    h[:, 10:14] = rng.integers(5, 12, (40, 4))
    h += rng.integers(0, 2, h.shape).astype(np.int32)
    t = math.tan(math.radians(dune_field.SHADOW_DEGREES)) * dune_field.SLAB_ASPECT
    brute = np.full(h.shape, -np.inf)
    for k in range(1, h.shape[1]):
        brute = np.maximum(brute, np.roll(h, k, axis=1) - k * t)
    assert np.array_equal(dune_field.shadow_mask(h, (1.0, 0.0), t), brute > h)
    # Off the axes the upwind points fall between cells. A cone on level ground against the
    # continuous shadow it casts (the cone itself, sampled finely along the wind) on the ground.
    n, radius, height = 128, 20.0, 30.0
    y, x = np.mgrid[0:n, 0:n] + 0.5
    u = np.array([math.cos(0.6), math.sin(0.6)])

    def cone(px, py):
        return np.maximum(height * (1 - np.hypot(px - 40.0, py - 40.0) / radius), 0.0)

    h = np.round(cone(x, y)).astype(np.int32)
    exact = np.zeros(h.shape, bool)
    for k in np.arange(0.05, 100.0, 0.05):
        exact |= cone(x - k * u[0], y - k * u[1]) - k * t > 0
    ground = h == 0
    found = dune_field.shadow_mask(h, u, t)
    assert exact[ground].sum() > 200  # a long shadow to compare
    assert np.mean(found[ground] != exact[ground]) < 0.01


def test_one_seed_one_field():
    first = dune_field.grow((48, 48), 4.0, 7, steps=20)
    again = dune_field.grow((48, 48), 4.0, 7, steps=20)
    other = dune_field.grow((48, 48), 4.0, 8, steps=20)
    assert np.array_equal(first.slabs, again.slabs)
    assert not np.array_equal(first.slabs, other.slabs)


def test_slip_faces_stand_at_repose_and_nothing_steeper(transverse):
    slope, along = triangle_slopes(transverse)
    assert slope.max() <= 34.0  # nowhere steeper than dry sand stands
    slip = (along > 0.5) & (slope > 20.0)  # facing downwind: the lee
    assert slip.mean() > 0.05
    assert 30.0 <= np.median(slope[slip]) <= 34.0
    windward = (along < -0.5) & (slope > 2.0)
    assert windward.any() and 5.0 <= np.median(slope[windward]) <= 15.0
    # Lee faces are steep, windward backs gentle: the asymmetry that makes a dune read as one.
    assert np.percentile(slope[along > 0.5], 90) > np.percentile(slope[along < -0.5], 90) + 8


def test_no_slab_stairs_at_render_scale(transverse):
    """Slabs stand in steps a third of a cell high. Read at the fine lattice's own spacing, a
    windward back bends by under half a slab between neighbours (second differences along the
    wind); the slabs as they lie, read through the same spline, bend by 1.3 slabs (measured)."""
    surface, fine = transverse["surface"], transverse["facts"]["fine_cell"]
    slab = fine / dune_field.SLAB_ASPECT
    along = np.arange(-40.0, 40.0, fine)
    x, y = np.meshgrid(along, along)
    c, s = math.cos(WIND), math.sin(WIND)
    z = surface.heights(x * c - y * s, x * s + y * c)  # rows run along the wind
    bend = np.abs(z[:, 2:] - 2 * z[:, 1:-1] + z[:, :-2])
    gy, gx = np.gradient(z, fine)
    slope = np.degrees(np.arctan(np.hypot(gx, gy)))[:, 1:-1]
    back = (slope > 3) & (slope < 18)
    assert np.median(bend[back]) < 0.15 * slab and np.percentile(bend[back], 99) < 0.5 * slab


def wavevector_angle(z):
    """The mean direction of the height's wavevectors (doubled-angle mean of the power spectrum)
    in degrees, and how strongly one direction holds (0..1)."""
    power = np.abs(np.fft.fft2(z - z.mean())) ** 2
    ky, kx = np.fft.fftfreq(z.shape[0])[:, None], np.fft.fftfreq(z.shape[1])[None, :]
    angle = np.arctan2(ky + 0 * kx, kx + 0 * ky)
    c, s = (power * np.cos(2 * angle)).sum(), (power * np.sin(2 * angle)).sum()
    return math.degrees(0.5 * math.atan2(s, c)), math.hypot(c, s) / power.sum()


def angle_between(a, b):
    """Difference of two axial directions in degrees, 0..90."""
    return abs((a - b + 90.0) % 180.0 - 90.0)


def test_crests_run_across_the_wind(transverse):
    angle, strength = wavevector_angle(transverse["z"])
    assert angle_between(angle, math.degrees(WIND)) < 10.0 and strength > 0.3


def crest_to_slip_face(heights, step, spacing):
    """Along-wind profiles (rows of heights, step metres apart): for each crest higher than half
    the tallest, the distance downwind at which the ground first falls at 25 degrees, if it does
    within a quarter spacing."""
    distances = []
    for z in heights:
        slope = np.degrees(np.arctan(-np.gradient(z, step)))  # falling downwind
        crests = np.flatnonzero((z[1:-1] > z[:-2]) & (z[1:-1] >= z[2:]) & (z[1:-1] > 0.5 * z.max())) + 1
        for crest in crests:
            ahead = slope[crest:crest + int(0.25 * spacing / step)]
            distances.append(np.argmax(ahead > 25.0) * step if len(ahead) and ahead.max() > 25.0 else np.inf)
    return np.array(distances)


def test_crests_are_sharp(transverse):
    """Downwind of a crest that ends in a slip face, the face begins within a tenth of the spacing
    on most of them (the model rounds a crest over about 1.6 m of a 24 m spacing, measured); a
    rounded crest of the same height and spacing (a sine) never reaches 25 degrees at all."""
    surface = transverse["surface"]
    c, s = math.cos(WIND), math.sin(WIND)
    step = 0.1
    t = np.arange(-48.0, 48.0, step)
    rows = [surface.heights(t * c - o * s, t * s + o * c) for o in np.linspace(-40, 40, 41)]
    distances = crest_to_slip_face(rows, step, SPACING)
    faced = distances[np.isfinite(distances)]
    assert len(faced) > 40 and len(faced) > 0.4 * len(distances)
    assert np.mean(faced < SPACING / 10) > 0.75
    height = np.percentile(transverse["z"], 99) - np.percentile(transverse["z"], 1)
    sine = 0.5 * height * np.cos(2 * np.pi * t / SPACING)
    assert not np.isfinite(crest_to_slip_face([sine], step, SPACING)).any()


@pytest.mark.parametrize("waves", [(8, 0), (6, 8), (0, 5)])
def test_the_reported_spacing_is_across_the_crests_whichever_way_they_run(waves):
    """Straight crests at any angle (linear dunes lie along the wind): the spacing reported is
    the distance across them, not along the lattice's x (which reads 32 cells for the second)."""
    y, x = np.mgrid[0:256, 0:256]
    z = 3.0 + np.sin(2.0 * np.pi * (waves[0] * x + waves[1] * y) / 256.0)
    assert dunes.spacing_cells(z, smooth=1.0) == pytest.approx(256.0 / math.hypot(*waves), rel=0.01)


def test_spacing_and_height_follow_the_setting(transverse):
    """The spacing asked for, measured on the mesh as the along-wind spectral peak; heights
    about a tenth of it (real transverse dunes: 1/20 to 1/8)."""
    surface = transverse["surface"]
    c, s = math.cos(WIND), math.sin(WIND)
    t = np.arange(0.0, 4 * 96.0, 0.25)
    profiles = [surface.heights(t * c - o * s, t * s + o * c) for o in np.linspace(0, 96, 25)]
    power = np.mean([np.abs(np.fft.rfft(p - p.mean())) ** 2 for p in profiles], axis=0)
    k = np.arange(len(power))
    peak = np.argmax(power[1:]) + 1
    band = (k >= peak / 2) & (k <= 2 * peak)
    spacing = len(t) * 0.25 / (np.sum(k[band] * power[band]) / power[band].sum())
    assert abs(spacing / SPACING - 1) < 0.2
    height = np.percentile(transverse["z"], 99) - np.percentile(transverse["z"], 1)
    assert SPACING / 20 < height < SPACING / 6


def components(mask):
    """Connected components (4-neighbours, not wrapping) of a boolean grid: labels, 0 outside."""
    labels = np.where(mask, np.arange(1, mask.size + 1).reshape(mask.shape), 0)
    while True:
        spread = labels.copy()
        for axis in (0, 1):
            for shift in (1, -1):
                moved = np.roll(labels, shift, axis=axis)
                edge = [slice(None)] * 2
                edge[axis] = 0 if shift == 1 else -1
                moved[tuple(edge)] = 0
                spread = np.where(mask & (moved > 0), np.maximum(spread, moved), spread)
        if np.array_equal(spread, labels):
            return labels
        labels = spread


def test_scarce_sand_gathers_into_barchans_with_horns_downwind(barchans):
    z = barchans["z"]
    assert np.mean(z < BARE) > 0.5  # bare ground between the dunes
    labels = components(z > 0.15 * z.max())
    n = z.shape[0]
    y, x = np.mgrid[0:n, 0:n] * barchans["cell"]
    verdicts = []
    for label in np.unique(labels[labels > 0]):
        inside = labels == label
        touches_edge = inside[0].any() or inside[-1].any() or inside[:, 0].any() or inside[:, -1].any()
        if inside.sum() < 200 or touches_edge:
            continue
        weight = z[inside]
        centre = np.sum(x[inside] * weight) / weight.sum()
        across = y[inside]
        # The horns: the dune's ends across the wind (its outer tenth on either side).
        low, high = np.percentile(across, [10, 90])
        horns = (across <= low) | (across >= high)
        verdicts.append(np.mean(x[inside][horns]) > centre)
    assert len(verdicts) >= 3
    assert np.mean(verdicts) >= 0.7


def test_more_sand_covers_more_ground(barchans, transverse):
    assert np.mean(barchans["z"] < BARE) > np.mean(transverse["z"] < BARE) + 0.15


def gross_transport_trend(winds):
    """Rubin and Hunter (1987): crests take the trend across which the gross transport (the sum
    of each wind's share times |cos| of its angle to the crest normal) is greatest. Returns the
    crest normal in degrees."""
    normals = np.radians(np.arange(0.0, 180.0, 0.25))
    gross = sum(share * np.abs(np.cos(normals - angle)) for angle, share in winds)
    return math.degrees(normals[np.argmax(gross)])


@pytest.mark.parametrize("second, share", [(120.0, 0.5), (150.0, 0.5),
                                            pytest.param(120.0, 0.3, marks=pytest.mark.sweep)])
def test_two_winds_follow_the_gross_transport_rule(second, share):
    blowing, frame = dunes.winds(math.radians(second), share)
    field = dune_field.grow((160, 160), dunes.supply_slabs(3.0), 0, blowing)
    z = dune_surface.gaussian_periodic(field.slabs.astype(np.float64), 2.0)
    angle, strength = wavevector_angle(z)
    predicted = gross_transport_trend([(0.0, 1 - share), (math.radians(second), share)])
    assert strength > 0.15
    assert angle_between(angle + math.degrees(frame), predicted) < 12.0
    if share == 0.5:  # equal winds more than 90 degrees apart: linear dunes along the resultant
        assert angle_between(predicted, second / 2 + 90) < 1.0
