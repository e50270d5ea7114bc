"""The numpy painter against analytic expectations for a straight walk on flat ground.

Expected contact points come from the walk's formula (x = k * stride, y = +-stance / 2),
not from the planner; centres are measured on the painted image as depth-weighted
centroids (a heel ratio of 1 makes the sole symmetric about its centre).
"""

import math

import numpy as np
import pytest

from core import footprints as fp
from core import paths
from core import sole as soles

STRIDE, STANCE = 0.7, 0.2
TEXEL = 0.005  # metres; the rim peak of a round-ended sole lands on a texel centre
DEPTH, RIM = 0.03, 0.008  # the group's sockets: metres per unit of R and of G
TOLERANCE = 1e-4
CHANNEL_TOLERANCE = 1e-6  # unit-free image channels (0..1): float32 round-off, no more


def straight_walk(steps=8, frames_per_metre=24.0):
    length = STRIDE * (steps - 1)
    frames = np.arange(int(length * frames_per_metre) + 3, dtype=float)  # a little past the last step
    positions = np.stack([frames / frames_per_metre, np.zeros_like(frames), np.zeros_like(frames)], 1)
    return paths.plan_steps(positions, frames, STRIDE, STANCE), frames


def flat_axes(forward):
    f = forward[:, :2]
    return f, np.stack([-f[:, 1], f[:, 0]], axis=1)


def aligned_region(centres, sole):
    """A region whose texel centres fall on every print centre (multiples of TEXEL)."""
    pad = sole.reach(TEXEL) + 10 * TEXEL
    low = np.floor((centres.min(0) - pad) / TEXEL) * TEXEL - TEXEL / 2
    high = centres.max(0) + pad
    size = np.ceil((high - low) / TEXEL).astype(int)
    return fp.Region(low[0], low[1], TEXEL, size[0], size[1])


def texel_of(region, point):
    return (int(np.floor((point[1] - region.y0) / region.texel)),
            int(np.floor((point[0] - region.x0) / region.texel)))


@pytest.fixture
def painted():
    sole = soles.Sole(heel_ratio=1.0, edge=3 * TEXEL)  # the wall's top on a texel edge
    steps, frames = straight_walk()
    forward, lateral = flat_axes(steps["forward"])
    centres = steps["contact"][:, :2]
    region = aligned_region(centres, sole)
    image = fp.paint(centres, forward, lateral, steps["birth"], 1.0, region, sole, (0, frames[-1]))
    return sole, steps, region, image, frames


def test_planner_matches_the_walk_formula():
    steps, frames = straight_walk()
    k = np.arange(8)
    expected = np.stack([k * STRIDE, np.where(k % 2 == 0, STANCE / 2, -STANCE / 2), 0 * k], 1)
    np.testing.assert_allclose(steps["contact"], expected, atol=1e-12)
    np.testing.assert_allclose(steps["birth"], k * STRIDE * 24.0, atol=1e-9)
    np.testing.assert_allclose(steps["heading"], 0.0, atol=1e-12)
    assert list(steps["side"]) == [1, -1] * 4


def test_print_centres_within_half_a_texel(painted):
    sole, steps, region, image, _ = painted
    depth = image[..., 0].astype(np.float64)
    rows, cols = np.indices(depth.shape)
    x = region.x0 + (cols + 0.5) * TEXEL
    y = region.y0 + (rows + 0.5) * TEXEL
    k = np.arange(8)
    expected = np.stack([k * STRIDE, np.where(k % 2 == 0, STANCE / 2, -STANCE / 2)], 1)
    for centre in expected:
        near = (np.hypot(x - centre[0], y - centre[1]) < sole.reach(TEXEL)) & (depth > 0)
        weight = depth[near]
        measured = np.array([(x[near] * weight).sum(), (y[near] * weight).sum()]) / weight.sum()
        assert np.abs(measured - centre).max() < 0.5 * TEXEL


def test_depth_and_rim_at_their_analytic_places(painted):
    sole, steps, region, image, _ = painted
    for centre, side in zip(steps["contact"][:, :2], steps["side"], strict=True):
        row, col = texel_of(region, centre)
        assert abs(DEPTH * image[row, col, 0] - DEPTH) < TOLERANCE
        assert abs(image[row, col, 1]) <= CHANNEL_TOLERANCE
        # Rim peak: half a rim band beyond the wall outside the straight edge, away from the path.
        offset = sole.width / 2 + sole.edge_width(TEXEL) + sole.rim_band(TEXEL) / 2
        row, col = texel_of(region, centre + (0.0, side * offset))
        assert abs(RIM * image[row, col, 1] - RIM) < TOLERANCE
    assert image[..., 0].max() <= 1.0 and image[..., 1].max() <= 1.0


def test_zero_outside_the_stamp_radius(painted):
    sole, steps, region, image, _ = painted
    rows, cols = np.indices(image.shape[:2])
    x = region.x0 + (cols + 0.5) * TEXEL
    y = region.y0 + (rows + 0.5) * TEXEL
    nearest = np.min([np.hypot(x - cx, y - cy) for cx, cy in steps["contact"][:, :2]], axis=0)
    outside = nearest > sole.reach(TEXEL)
    assert outside.any() and not image[outside].any()
    flat_bottom = image[nearest < sole.width / 2 - TEXEL, 0]  # the sole's floor: inside its outline
    assert np.abs(flat_bottom - 1.0).max() <= CHANNEL_TOLERANCE


def test_birth_channel_reveals_each_print_when_the_walker_passes(painted):
    _, steps, region, image, frames = painted
    for centre, birth in zip(steps["contact"][:, :2], steps["birth"], strict=True):
        row, col = texel_of(region, centre)
        assert abs(image[row, col, 2] * frames[-1] - birth) < 1e-3
        before = fp.revealed_height(image, DEPTH, RIM, birth - 1, (0, frames[-1]))
        after = fp.revealed_height(image, DEPTH, RIM, birth, (0, frames[-1]))
        assert abs(before[row, col]) < TOLERANCE and abs(after[row, col] + DEPTH) < TOLERANCE


def test_toe_is_wider_than_heel_and_points_forward():
    sole = soles.Sole()  # heel ratio 0.75
    region = fp.Region(-0.25, -0.25, TEXEL, 100, 100)
    for heading in (0.0, 2.0):
        f = np.array([[np.cos(heading), np.sin(heading)]])
        image = fp.paint([[0.0, 0.0]], f, [[-f[0, 1], f[0, 0]]], [0.0], 1.0, region, sole)
        rows, cols = np.indices(image.shape[:2])
        along = ((region.x0 + (cols + 0.5) * TEXEL) * f[0, 0] + (region.y0 + (rows + 0.5) * TEXEL) * f[0, 1])
        pressed = image[..., 3] > 0.5
        assert pressed[along > 0.05].sum() > 1.2 * pressed[along < -0.05].sum()


def test_a_later_sole_flattens_an_earlier_rim_and_depth_stays_bounded():
    sole = soles.Sole(heel_ratio=1.0)
    region = fp.Region(-0.4, -0.4, TEXEL, 160, 160)
    forward, lateral = np.array([[1.0, 0.0]] * 2), np.array([[0.0, 1.0]] * 2)
    centres = np.array([[0.0, 0.0], [0.0, 0.08]])  # the second sole lies over the first's rim
    rim_point = texel_of(region, (0.0, sole.width / 2 + sole.rim_band(TEXEL) / 2))
    later_second = fp.paint(centres, forward, lateral, [0.0, 1.0], 1.0, region, sole)
    later_first = fp.paint(centres, forward, lateral, [1.0, 0.0], 1.0, region, sole)
    assert abs(later_second[rim_point][1]) <= CHANNEL_TOLERANCE  # flattened by the later sole
    assert later_first[rim_point][1] > 0.5  # the earlier sole does not flatten a later rim
    assert later_second[..., 0].max() <= 1.0


def test_batches_compose_like_one_pass(monkeypatch):
    steps, frames = straight_walk(steps=40)
    # A stride shorter than the foot overlaps prints; the walk back crosses them again.
    forward, lateral = flat_axes(steps["forward"])
    centres = steps["contact"][:, :2] * (0.2, 1.0)
    births = steps["birth"]
    region = fp.fit_region(centres, soles.Sole().reach(), 400, 0.05)
    whole = fp.paint(centres, forward, lateral, births, 1.0, region)
    monkeypatch.setattr(fp, "CHUNK_ENTRIES", 500)
    batched = fp.paint(centres, forward, lateral, births, 1.0, region)
    np.testing.assert_allclose(batched, whole, atol=1e-6)


def test_a_hundred_prints_on_one_spot_stay_bounded():
    rng = np.random.default_rng(1)
    n = 100
    angle = rng.uniform(0, 2 * np.pi, n)
    forward = np.stack([np.cos(angle), np.sin(angle)], 1)
    lateral = np.stack([-forward[:, 1], forward[:, 0]], 1)
    scales = rng.uniform(0.5, 1.5, n)
    region = fp.Region(-0.5, -0.5, TEXEL, 200, 200)
    image = fp.paint(rng.normal(0, 0.02, (n, 2)), forward, lateral, rng.uniform(0, 10, n), scales,
                     region, frame_range=(0, 10))
    assert np.isfinite(image).all()
    assert image[..., 0].max() <= scales.max() + 1e-6 and image[..., 1].max() <= scales.max() + 1e-6
    assert 0.0 <= image[..., 2].min() and image[..., 2].max() <= 1.0


def test_bad_prints_are_skipped_not_painted():
    region = fp.Region(-0.5, -0.5, TEXEL, 200, 200)
    centres = [[0.0, 0.0], [np.nan, 0.0], [0.1, 0.0], [0.2, np.inf]]
    forward = [[1.0, 0.0], [1.0, 0.0], [0.0, 0.0], [1.0, 0.0]]  # print 3 has a degenerate frame
    lateral = [[0.0, 1.0]] * 4
    image = fp.paint(centres, forward, lateral, [0, 1, 2, 3], [1.0, 1.0, 1.0, 1.0], region)
    assert np.isfinite(image).all() and abs(image[..., 0].max() - 1.0) <= CHANNEL_TOLERANCE


@pytest.mark.parametrize("resolution", [1, 2, 7])
def test_tiny_resolutions(resolution):
    steps, frames = straight_walk()
    forward, lateral = flat_axes(steps["forward"])
    region = fp.fit_region(steps["contact"][:, :2], soles.Sole().reach(), resolution)
    image = fp.paint(steps["contact"][:, :2], forward, lateral, steps["birth"], 1.0, region)
    assert image.shape[1] == resolution and np.isfinite(image).all() and image.max() <= 1.0


def test_planner_refuses_a_walker_that_stands_still():
    with pytest.raises(paths.PathError, match="does not move"):
        paths.plan_steps(np.zeros((10, 3)), np.arange(10), 0.7, 0.2)
    with pytest.raises(paths.PathError, match="stride"):
        paths.plan_steps(np.eye(3), np.arange(3), 0.0, 0.2)


def test_heading_follows_a_circle_sampled_per_frame():
    radius, frames = 5.0, np.arange(241, dtype=float)
    angle = frames / 240 * np.pi  # half a circle over 240 frames
    positions = np.stack([radius * np.cos(angle), radius * np.sin(angle), 0 * angle], 1)
    steps = paths.plan_steps(positions, frames, 0.7, 0.2)
    centre_angle = np.interp(steps["birth"], frames, angle)
    expected = centre_angle + np.pi / 2
    error = np.angle(np.exp(1j * (steps["heading"] - expected)))
    assert np.abs(np.degrees(error)).max() < 0.01
    # Toed out: the left foot (side +1) turns left of the tangent, the right turns right, unit.
    toed = paths.plan_steps(positions, frames, 0.7, 0.2, toe_out=paths.TOE_OUT)
    turn = np.angle(np.exp(1j * (toed["heading"] - steps["heading"])))
    np.testing.assert_allclose(turn, steps["side"] * paths.TOE_OUT, atol=1e-9)
    np.testing.assert_allclose(toed["forward"][:, :2], np.stack([np.cos(toed["heading"]),
                                                                 np.sin(toed["heading"])], 1), atol=1e-9)
    np.testing.assert_array_equal(toed["contact"], steps["contact"])


@pytest.mark.parametrize("depth", [0.01, 0.05, 0.12])
def test_walls_stand_at_the_angle_of_repose(depth):
    """Dry sand crumbles: across the wall the painted depth falls no steeper than 34 degrees,
    and reaches it (a wall of the sole's own outline would stand at 76 degrees for 5 cm)."""
    texel = 0.002
    sole = soles.Sole(heel_ratio=1.0, edge=soles.wall_width(depth), rim_width=0.0)
    region = fp.Region(-0.3, -0.01, texel, 300, 10)
    image = fp.paint(np.array([[0.0, 0.0]]), np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]),
                     np.array([1.0]), 1.0, region, sole, (0.0, 2.0))
    profile = depth * image[5, :, 0].astype(np.float64)  # along the sole's length, through its centre
    steepest = math.degrees(math.atan(np.abs(np.diff(profile)).max() / texel))
    print(f"depth {depth * 100:g} cm: wall {soles.wall_width(depth) * 100:.1f} cm wide, "
          f"steepest {steepest:.2f} deg")
    # The wall's straight part stands at 34 degrees exactly: float32 texels put it 1e-4 either side.
    assert 33.0 <= steepest <= 34.01
    assert profile.max() == pytest.approx(depth, rel=1e-6)


def test_a_runs_print_is_deepest_at_the_toe():
    """toe_bias b: depth (1 + b a / (L/2)) on the sole's floor, a from the middle toward the toe;
    the rim and the print's outline do not change. Reference: that line, at texel centres."""
    sole = soles.Sole()
    centre = np.array([[0.0, 0.0]])
    region = aligned_region(centre, sole)
    even = fp.paint(centre, [[1.0, 0.0]], [[0.0, 1.0]], [0.0], 1.0, region, sole)
    tilted = fp.paint(centre, [[1.0, 0.0]], [[0.0, 1.0]], [0.0], 1.0, region, sole, toe_bias=[0.4])
    row = texel_of(region, (0.0, 0.0))[0]
    xs = region.x0 + (np.arange(region.width) + 0.5) * TEXEL
    floor = even[row, :, 0] > 1.0 - 1e-6
    assert floor.sum() > 30
    expected = 1.0 + 0.4 * xs[floor] / (sole.length / 2)
    assert np.abs(tilted[row, floor, 0] - expected).max() < 1e-5
    assert tilted[row, floor, 0].max() > 1.35 and tilted[row, floor, 0].min() < 0.65
    assert np.array_equal(tilted[..., 1:], even[..., 1:])  # rim, birth and coverage as before


def test_the_wind_fills_windward_prints_faster():
    """Refill rate (1 + 2 g)^3 on ground rising into the wind at gradient g (speed-up over a low
    hill, sand flux as the cube of the wind's speed), up to the angle of repose; 1 elsewhere."""
    tilt = math.radians(20.0)
    facing_plus_x = (math.sin(tilt), 0.0, math.cos(tilt))
    assert fp.windward_refill_rate((0, 0, 1), (5, 0, 0)) == pytest.approx(1.0)  # flat
    assert fp.windward_refill_rate(facing_plus_x, (0, 0, 0)) == pytest.approx(1.0)  # calm
    assert fp.windward_refill_rate(facing_plus_x, (3, 0, 0)) == pytest.approx(1.0)  # lee
    assert fp.windward_refill_rate(facing_plus_x, (-3, 0, 0)) == pytest.approx((1 + 2 * math.tan(tilt)) ** 3)
    cliff = (math.sin(1.2), 0.0, math.cos(1.2))
    assert fp.windward_refill_rate(cliff, (-3, 0, 0)) == pytest.approx((1 + 2 * math.tan(soles.REPOSE)) ** 3)
    image = np.zeros((1, 1, 4), np.float32)
    image[0, 0] = (1.0, 0.0, 0.0, 1.0)  # a print born at frame 0
    left = [fp.revealed_height(image, 0.03, 0.0, 40.0, (0, 100), refill=40.0, normal=normal, wind=(-3, 0, 0))
            for normal in ((0, 0, 1), facing_plus_x)]
    assert left[0][0, 0] == pytest.approx(-0.03 * math.exp(-1.0), rel=1e-5)
    assert left[1][0, 0] == pytest.approx(-0.03 * math.exp(-(1 + 2 * math.tan(tilt)) ** 3), rel=1e-4)


def test_eevee_levels_halve_the_longest_kept_edge_to_the_target():
    """Two faces: a 1 m square (kept or not) and a 0.5 m square; levels halve the longest kept edge
    until it is at most the target, capped."""
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                       [2, 0, 0], [2.5, 0, 0], [2.5, 0.5, 0], [2, 0.5, 0]], float)
    corner_vertex = np.arange(8)
    corner_face = np.repeat([0, 1], 4)
    levels = fp.eevee_levels
    assert levels(points, corner_vertex, corner_face, [True, True], 0.03) == 6  # 1 m / 2^6 = 1.6 cm
    assert levels(points, corner_vertex, corner_face, [False, True], 0.03) == 5  # 0.5 m / 2^5
    assert levels(points, corner_vertex, corner_face, [True, True], 0.01) == 6  # the cap
    assert levels(points, corner_vertex, corner_face, [True, True], 2.0) == 0
    assert levels(points, corner_vertex, corner_face, [False, False], 0.03) == 0


def test_a_foots_print_is_waisted_and_deepest_under_heel_and_ball():
    """A foot's sole (FOOT_ARCH, FOOT_WAIST): the floor is the set depth under the heel's and the
    toe's circle centres and FOOT_ARCH of it midway between; there the outline's inner half (+b,
    the lateral axis) is FOOT_WAIST as wide as a straight capsule's and its outer half unchanged;
    its walls still stand no steeper than the angle of repose."""
    texel, depth = 0.001, 0.04
    plain = soles.Sole(edge=soles.wall_width(depth), rim_width=0.0)
    foot = soles.Sole(edge=soles.wall_width(depth), rim_width=0.0, arch=soles.FOOT_ARCH,
                      waist=soles.FOOT_WAIST)
    region = fp.Region(-0.3, -0.3, texel, 600, 600)
    images = [fp.paint([[0.0, 0.0]], [[1.0, 0.0]], [[0.0, 1.0]], [0.0], 1.0, region, sole)
              for sole in (plain, foot)]
    xs = region.x0 + (np.arange(region.width) + 0.5) * texel
    heel, toe = foot.centres()
    middle = (heel + toe) / 2
    row = texel_of(region, (0.0, 0.0))[0]
    for at, expected in ((heel, 1.0), (toe, 1.0), (middle, soles.FOOT_ARCH)):
        col = int(np.argmin(np.abs(xs - at)))
        assert images[1][row, col, 0] == pytest.approx(expected, abs=2e-3)
    col = int(np.argmin(np.abs(xs - middle)))
    for half in (slice(row, None), slice(None, row)):  # inner (+y), outer (-y) from the centre row
        widths = [(image[half, col, 3] >= 1.0 - 1e-6).sum() * texel for image in images]
        expected = soles.FOOT_WAIST if half.start == row else 1.0
        assert widths[1] / widths[0] == pytest.approx(expected, abs=2 * texel / widths[0])
    across = depth * images[1][:, col, 0].astype(np.float64)
    along = depth * images[1][row, :, 0].astype(np.float64)
    steepest = max(np.abs(np.diff(profile)).max() for profile in (across, along)) / texel
    assert math.degrees(math.atan(steepest)) <= 34.05  # float32 round-off over a 1 mm texel
