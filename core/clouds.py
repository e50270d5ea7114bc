"""The cloud layer in numpy: the twin of the cloud node groups, the phase function, and the
geometry of the layer (what the camera can see of it, and where the weather map has cloud).

Model (seeds 001 and 003, with their errata fixed):
- h, the height fraction in the layer: (z - base) / thickness, clamped to 0..1.
- A type's height gradient: smoothstep(a, b, h) - smoothstep(c, d, h) with (a, b, c, d) from
  seed 001 for stratus, cumulus and cumulonimbus. Types in between blend the four numbers:
  lerp(lerp(stratus, cumulus, sat(2 t)), cumulonimbus, sat(2 t - 1)); the seed's inner lerp
  takes an unclamped 2 t, which extrapolates past cumulus for t > 0.5.
- The weather map's coverage: a 2D fBm noise n over the ground (looked up at a warped position,
  so outlines are fractal), cloud where n rises past an edge chosen so that the Coverage setting
  is the share of sky under cloud; precipitation
  makes clouds denser; a type per point.
- Shape: Perlin-Worley noise (Perlin fBm dilated by inverted Worley), times the gradient,
  remapped by the coverage (seed 001: remap(shape, 1 - coverage, 1, 0, 1) x coverage), eroded
  at the edges by a Worley fBm on a curl-like distorted position: wispy low (1 - worley),
  billowy at the top, and not at all at the base itself, so bases are flat; then sharpened
  (EDGE_GAIN) so the edges are crisp rather than a soft fade.
- Wind: every noise is sampled at p - wind x time; the shape and detail also at - skew x h
  along the wind, so tops lean downwind.
"""

import math

import numpy as np

from . import noise_perlin as noise
from .shaping import henyey_greenstein, smoothstep, wind_direction  # noqa: F401 (the clouds' API)

GRADIENTS = {  # seed 001: (a, b, c, d) of smoothstep(a, b, h) - smoothstep(c, d, h)
    "STRATUS": (0.0, 0.065, 0.203, 0.371),
    # Seed 001's cumulus is (0, 0.156, 0.468, 0.674): a soft base and every top at about the same
    # height. Ours rises fast (flat bases) and falls over a wide band, so stronger shapes reach
    # higher: domes, tall and short clouds side by side.
    "CUMULUS": (0.0, 0.05, 0.2, 0.7),
    "CUMULONIMBUS": (0.0, 0.188, 0.818, 1.0),
}
TYPE_VALUES = {"STRATUS": 0.0, "CUMULUS": 0.5, "CUMULONIMBUS": 1.0}
MAP_DETAIL = 2.0  # octaves - 1 of the weather map's noise
TYPE_MAP_SCALE = 2.5  # the Mixed type's map varies this many times more slowly than coverage
# Coverage -> the weather noise's edge (coverage_edge): a fit to the quantiles of the map's noise
# (2D fBm, MAP_DETAIL; 2e6 points of core.noise_perlin); MAP_SOFTNESS: width of the coverage ramp
# above the edge, in noise units.
EDGE_FIT = (0.49993419, 0.06642161, -0.0008259)  # edge = c0 + c1 L + c3 L^3, L = ln((1 - c) / c)
EDGE_RANGE = (0.006, 0.994)  # where the fit is monotone; 0 and 1 mean none and all
# The map is looked up at a warped position (2D fBm displacements of up to WARP / 2 map cells at
# several scales): coastlines as ragged as real cloud outlines (D about 1.35) rather than the
# smooth contours of a few octaves, with the noise's value distribution (so the calibration) kept.
WARP = 1.2
WARP_DETAIL = 4.0
WARP_ROUGHNESS = 0.6
WARP_FREQUENCY = 2.0
WARP_OFFSETS = (31.7, 77.3)  # decorrelate the x and y displacements
MAP_SOFTNESS = 0.35  # wide: coverage stays below 1 inside the map's blobs, so the shape noise carves clouds
# The shape noise carves clouds out of the map's coverage ramp, so less sky is under opaque cloud
# (T < 0.5 seen straight up) than the ramp's own share: the ramp starts this far below the
# quantile edge to make up for it (fitted on the twin at coverages 0.2, 0.5 and 0.8, map scales
# 2000 and 6000 m; held by tests/test_clouds.py).
OPAQUE_SHIFT = 0.177
SHAPE_DETAIL = 4.0
SHAPE_ROUGHNESS = 0.62  # 2^-H with H = 0.7: outlines of fractal dimension about 2 - H (Lovejoy's 1.35)
EDGE_GAIN = 3.0  # the eroded density reaches full within a third of its range: crisp edges, not a fade
# The signed cloudiness runs on linearly to +-CLOUDINESS_RANGE before it is clamped, so a voxel grid
# of it interpolates across an edge as the field does (a clamp at +-1 would put every edge at a
# voxel's middle: 0.026 less sky under cloud at 150 m voxels).
CLOUDINESS_RANGE = 4.0
BASE_CALM = 10.0  # erosion grows from none at the base over the lowest 1 / BASE_CALM: flat bases
DETAIL_WEIGHTS = (0.625, 0.25, 0.125)  # Worley fBm: three octaves, each twice the frequency
PRECIPITATION_GAIN = 2.0  # full precipitation triples the density
SEED_STEP = np.array([37.17, 91.43, 13.71])  # noise-space offset per seed
CURL_OFFSET = np.array([19.1, 47.3, 71.9])  # decorrelates the second distortion noise



def remap(x, low, high, new_low, new_high, clamp=True):
    """Blender's Map Range (linear): 0 where low == high."""
    x, low, high = np.broadcast_arrays(*(np.asarray(v, np.float64) for v in (x, low, high)))
    span = high - low
    t = np.where(span != 0, (x - low) / np.where(span != 0, span, 1.0), 0.0)
    value = new_low + t * (new_high - new_low)
    return np.clip(value, min(new_low, new_high), max(new_low, new_high)) if clamp else value


def type_gradient(cloud_type):
    """(a, b, c, d) for a type 0 (stratus) .. 0.5 (cumulus) .. 1 (cumulonimbus), shape (..., 4)."""
    t = np.asarray(cloud_type, np.float64)[..., None]
    stratus, cumulus, cumulonimbus = (np.array(GRADIENTS[k]) for k in ("STRATUS", "CUMULUS", "CUMULONIMBUS"))
    low = stratus + np.clip(2.0 * t, 0.0, 1.0) * (cumulus - stratus)
    return low + np.clip(2.0 * t - 1.0, 0.0, 1.0) * (cumulonimbus - low)


def height_gradient(height_fraction, cloud_type):
    """Density profile of a type over the height fraction, 0..1."""
    a, b, c, d = np.moveaxis(type_gradient(cloud_type), -1, 0)
    return np.clip(smoothstep(a, b, height_fraction) - smoothstep(c, d, height_fraction), 0.0, 1.0)


def height_fraction(z, base, thickness):
    return np.clip((np.asarray(z, np.float64) - base) / thickness, 0.0, 1.0)


def coverage_edge(coverage):
    """The weather noise value above which there is cloud, for a Coverage setting: the noise's
    (1 - coverage) quantile, within 0.004 over 2 % .. 98 % (tests/test_cloud_twins.py). Coverage 0
    and 1 move the edge far outside the noise's range: no cloud, cloud everywhere."""
    c = np.asarray(coverage, np.float64)
    kept = np.clip(c, *EDGE_RANGE)
    odds = np.log((1.0 - kept) / kept)
    edge = EDGE_FIT[0] + EDGE_FIT[1] * odds + EDGE_FIT[2] * odds ** 3
    return edge + 10.0 * (c <= 0.0) - 10.0 * (c >= 1.0)


def seed_offset(seed):
    """Noise-space offset of a seed (applied after scaling, so it moves the pattern, not the size)."""
    return SEED_STEP * float(seed)


def drift(wind, time):
    """How far the air has carried the clouds at a time: wind x time, per axis."""
    return np.asarray(wind, np.float64) * float(time)


def weather_noise(xy, map_scale, seed):
    """The weather map's noise at world points xy (..., 2) (already drifted)."""
    points = np.asarray(xy, np.float64) / map_scale + seed_offset(seed)[:2]
    shift = [noise.fbm(noise.perlin_2d, points * WARP_FREQUENCY + offset, WARP_DETAIL, WARP_ROUGHNESS)
             .astype(np.float64) - 0.5 for offset in WARP_OFFSETS]
    warped = points + WARP * np.stack(shift, axis=-1)
    return noise.fbm(noise.perlin_2d, warped, MAP_DETAIL).astype(np.float64)


def map_coverage(weather, coverage):
    """Coverage channel 0..1 from the weather noise: 0 below the edge (less OPAQUE_SHIFT), 1
    MAP_SOFTNESS above."""
    edge = coverage_edge(coverage) - OPAQUE_SHIFT
    return smoothstep(edge, edge + MAP_SOFTNESS, weather)


def mixed_type(xy, map_scale, seed):
    """Cloud type 0..1 over the ground for the Mixed type: a slower noise, stretched to 0..1."""
    points = np.asarray(xy, np.float64) / (map_scale * TYPE_MAP_SCALE) + seed_offset(seed)[:2] + 5.5
    value = noise.fbm(noise.perlin_2d, points, 1.0).astype(np.float64)
    return np.clip((value - 0.3) / 0.4, 0.0, 1.0)



def shape_noise(points, shape_scale, seed):
    """Perlin-Worley noise at world points (..., 3): Perlin fBm dilated by inverted Worley."""
    q = np.asarray(points, np.float64) / shape_scale + seed_offset(seed)
    perlin = noise.fbm(noise.perlin_3d, q, SHAPE_DETAIL, SHAPE_ROUGHNESS).astype(np.float64)
    worley = 1.0 - noise.voronoi_f1(2.0 * q).astype(np.float64)
    return remap(perlin, worley - 1.0, 1.0, 0.0, 1.0)


def detail_noise(points, detail_scale, seed, curl, h):
    """Worley fBm on a curl-like distorted position, 0..1 (1 at feature points)."""
    q = np.asarray(points, np.float64) / detail_scale + seed_offset(seed)
    a = noise.fbm(noise.perlin_3d, q * 0.25, 0.0).astype(np.float64)
    b = noise.fbm(noise.perlin_3d, q * 0.25 + CURL_OFFSET, 0.0).astype(np.float64)
    shift = np.stack([a - 0.5, b - 0.5, np.zeros_like(a)], axis=-1) * (2.0 * curl * np.asarray(h)[..., None])
    q = q + shift
    total = 0.0
    for octave, weight in enumerate(DETAIL_WEIGHTS):
        total = total + weight * (1.0 - noise.voronoi_f1((2.0 ** octave) * q).astype(np.float64))
    return total


def cloudiness(points, p):
    """The layer's signed cloudiness at world points: the density over Density where positive
    (capped by density_from_cloudiness), how far from cloud where not. It varies smoothly across
    an edge, so a voxel grid of it, interpolated and then clamped, keeps the edge where it is; a
    grid of the clamped density would spread it over a voxel."""
    points = np.asarray(points, np.float64)
    xy = (points - drift(p["wind"], p["time"]))[..., :2]
    cover = map_coverage(weather_noise(xy, p["map_scale"], p["seed"]), p["coverage"])
    cloud_type = mixed_type(xy, p["map_scale"], p["seed"]) if p["cloud_type"] is None else p["cloud_type"]
    return shaped_cloudiness(points, {**p, "cloud_type": cloud_type}, cover)


def wet(precipitation):
    """Precipitation makes clouds denser: full precipitation triples the density."""
    return 1.0 + PRECIPITATION_GAIN * np.asarray(precipitation, np.float64)


def density_from_cloudiness(value, p):
    """Extinction per unit length from cloudiness: clamped to 0..wet, times the Density."""
    return np.clip(np.asarray(value, np.float64), 0.0, wet(p["precipitation"])) * p["density"]


def density(points, p):
    """Cloud density (extinction per scene unit) at world points (..., 3) for parameters p, a dict:
    base, thickness, coverage, map_scale, shape_scale, detail_scale, erosion, curl, skew,
    density, precipitation, cloud_type (0..1, or None for Mixed), seed, wind, time.
    """
    points = np.asarray(points, np.float64)
    xy = (points - drift(p["wind"], p["time"]))[..., :2]
    cover = map_coverage(weather_noise(xy, p["map_scale"], p["seed"]), p["coverage"])
    cloud_type = mixed_type(xy, p["map_scale"], p["seed"]) if p["cloud_type"] is None else p["cloud_type"]
    return density_from_cloudiness(shaped_cloudiness(points, {**p, "cloud_type": cloud_type}, cover), p)


def region_window(xy, region):
    """1 inside region (xmin, ymin, xmax, ymax, fade), falling smoothly to 0 at its sides over
    fade: the layer's density ends inside its box, so no side of the box ever shows."""
    if region is None:
        return 1.0
    xmin, ymin, xmax, ymax, fade = region
    fade = max(fade, 1e-6)
    xy = np.asarray(xy, np.float64)
    window = 1.0
    for axis, (low, high) in enumerate(((xmin, xmax), (ymin, ymax))):
        inside = xy[..., axis]
        window = window * smoothstep(0.0, fade, inside - low) * smoothstep(0.0, fade, high - inside)
    return window


def shaped_density(points, p, cover):
    """The Cloud Density group: density at points given the weather map's coverage there (p's
    cloud_type and precipitation stand for the map's other two channels; p["region"], optional,
    the box it fades out in)."""
    return density_from_cloudiness(shaped_cloudiness(points, p, cover), p)


def shaped_cloudiness(points, p, cover):
    """The Cloud Density group's Cloudiness output (see cloudiness)."""
    points = np.asarray(points, np.float64)
    carried = points - drift(p["wind"], p["time"])
    h = height_fraction(points[..., 2], p["base"], p["thickness"])
    skewed = carried - wind_direction(p["wind"]) * (p["skew"] * h)[..., None]
    shaped = shape_noise(skewed, p["shape_scale"], p["seed"]) * height_gradient(h, p["cloud_type"])
    with_cover = remap(shaped, 1.0 - cover, 1.0, 0.0, 1.0) * cover
    detail = detail_noise(skewed, p["detail_scale"], p["seed"], p["curl"], h)
    above_base = np.clip(BASE_CALM * h, 0.0, 1.0)
    modifier = (1.0 - detail) + above_base * (2.0 * detail - 1.0)
    eroded = remap(with_cover, modifier * p["erosion"] * above_base, 1.0, 0.0, 1.0, clamp=False)
    window = region_window(points[..., :2], p.get("region"))
    crisp = np.clip(EDGE_GAIN * eroded * window, -CLOUDINESS_RANGE, CLOUDINESS_RANGE)
    return crisp * wet(p["precipitation"])


# ---------------------------------------------------------------- phase



def dual_lobe(cos_theta, forward, back, back_weight):
    """Seed 003's two HG lobes, blended so the sum stays normalised."""
    return ((1.0 - back_weight) * henyey_greenstein(cos_theta, forward)
            + back_weight * henyey_greenstein(cos_theta, back))


def sphere_integral(phase, n=2000):
    """Integral of a phase over the sphere (Gauss-Legendre in cos theta; the phase is symmetric
    about the axis)."""
    nodes, weights = np.polynomial.legendre.leggauss(n)
    return float(2.0 * math.pi * np.sum(weights * phase(nodes)))


# ---------------------------------------------------------------- geometry


FADE_SHARE = 0.05  # the fade at the layer's sides: this share of Reach, at least a shape's size


def fade_width(shape_scale, reach):
    """How far inside its box's sides the layer fades out."""
    return max(shape_scale, FADE_SHARE * reach)


def layer_region(cameras_xy, seen_xy, reach, fade):
    """Box (xmin, ymin, xmax, ymax) holding the cameras out to reach in every direction and the
    points they see (an orthographic frame is wider than its camera), padded by the fade."""
    cameras = np.asarray(cameras_xy, np.float64).reshape(-1, 2)
    points = np.vstack([cameras - reach, cameras + reach, np.asarray(seen_xy, np.float64).reshape(-1, 2)])
    return (*(points.min(axis=0) - fade), *(points.max(axis=0) + fade))


def carried_region(region, wind, start, end):
    """The region in frame-0 space over times start..end: every region - wind x t."""
    xmin, ymin, xmax, ymax = region
    shifts = np.array([drift(wind, start)[:2], drift(wind, end)[:2]])
    return (xmin - shifts[:, 0].max(), ymin - shifts[:, 1].max(), xmax - shifts[:, 0].min(),
            ymax - shifts[:, 1].min())


def box_mesh(region, low, high):
    """Vertices and quads of the closed box over region from z = low to high."""
    xmin, ymin, xmax, ymax = region
    verts = np.array([(x, y, z) for z in (low, high) for y in (ymin, ymax) for x in (xmin, xmax)], np.float64)
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (1, 3, 7, 5), (3, 2, 6, 7), (2, 0, 4, 6)]
    return verts, faces


def has_cloud(bounds, samples, coverage_at):
    """Whether the weather map has cloud anywhere over bounds (xmin, ymin, xmax, ymax):
    coverage_at(xy) > 0 at any point of a samples x samples grid of cell centres."""
    xmin, ymin, xmax, ymax = bounds
    xs = xmin + (np.arange(samples) + 0.5) * (xmax - xmin) / samples
    ys = ymin + (np.arange(samples) + 0.5) * (ymax - ymin) / samples
    return bool((coverage_at(np.stack(np.meshgrid(xs, ys), axis=-1)) > 0).any())


# ---------------------------------------------------------------- views of the twin


def optical_depth_up(p, centre, size, pixels, heights=24):
    """Optical depth straight up through the layer over a square (side size, pixels x pixels,
    rows = y) centred at centre (x, y): the density summed over `heights` midpoints."""
    offsets = (np.arange(pixels) + 0.5) / pixels * size - size / 2
    xs, ys = np.meshgrid(centre[0] + offsets, centre[1] + offsets)
    step = p["thickness"] / heights
    tau = np.zeros_like(xs)
    for k in range(heights):
        z = np.full_like(xs, p["base"] + (k + 0.5) * step)
        tau += density(np.stack([xs, ys, z], axis=-1), p) * step
    return tau


def optical_depth_side(p, centre, width, depth, pixels, samples=24):
    """Optical depth seen from the side, looking along +y through a slab `depth` deep: an image
    width wide (pixels across, rows = z over the layer's thickness, square pixels)."""
    rows = max(1, int(round(pixels * p["thickness"] / width)))
    xs = centre[0] + (np.arange(pixels) + 0.5) / pixels * width - width / 2
    zs = p["base"] + (np.arange(rows) + 0.5) / rows * p["thickness"]
    gx, gz = np.meshgrid(xs, zs)
    step = depth / samples
    tau = np.zeros_like(gx)
    for k in range(samples):
        y = np.full_like(gx, centre[1] - depth / 2 + (k + 0.5) * step)
        tau += density(np.stack([gx, y, gz], axis=-1), p) * step
    return tau
