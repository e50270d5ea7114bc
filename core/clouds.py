"""The cloud layer in numpy: the twin of the cloud node groups, the phase function, and the
geometry of the layer (what the camera can see of it, and where the weather map has cloud).

Model (seeds 001 and 003, with their errata fixed):
- h, the height fraction in the layer: (z - base) / thickness, clamped to 0..1.
- A type's height gradient: smoothstep(a, b, h) - smoothstep(c, d, h) with (a, b, c, d) from
  seed 001 for stratus, cumulus and cumulonimbus. Types in between blend the four numbers:
  lerp(lerp(stratus, cumulus, sat(2 t)), cumulonimbus, sat(2 t - 1)); the seed's inner lerp
  takes an unclamped 2 t, which extrapolates past cumulus for t > 0.5.
- The weather map's coverage: a 2D fBm noise n over the ground, cloud where n rises past an
  edge chosen so that the Coverage setting is the share of sky under cloud; precipitation
  makes clouds denser; a type per point.
- Shape: Perlin-Worley noise (Perlin fBm dilated by inverted Worley), times the gradient,
  remapped by the coverage (seed 001: remap(shape, 1 - coverage, 1, 0, 1) x coverage), eroded
  at the edges by a Worley fBm on a curl-like distorted position: wispy at the base (1 - worley),
  billowy at the top.
- Wind: every noise is sampled at p - wind x time; the shape and detail also at - skew x h
  along the wind, so tops lean downwind.
"""

import math

import numpy as np

from . import noise_perlin as noise

GRADIENTS = {  # seed 001: (a, b, c, d) of smoothstep(a, b, h) - smoothstep(c, d, h)
    "STRATUS": (0.0, 0.065, 0.203, 0.371),
    "CUMULUS": (0.0, 0.156, 0.468, 0.674),
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
MAP_SOFTNESS = 0.06
# Columns turn opaque (T < 0.5 seen straight up) only where the coverage ramp passes about 0.56:
# remap(shape, 1 - coverage, 1, 0, 1) x coverage leaves thinner cover clear. So the ramp starts
# this far below the quantile edge (measured straight up at the defaults, tests/test_clouds.py).
OPAQUE_SHIFT = 0.0325
SHAPE_DETAIL = 3.0
DETAIL_WEIGHTS = (0.625, 0.25, 0.125)  # Worley fBm: three octaves, each twice the frequency
PRECIPITATION_GAIN = 2.0  # full precipitation triples the density
SEED_STEP = np.array([37.17, 91.43, 13.71])  # noise-space offset per seed
CURL_OFFSET = np.array([19.1, 47.3, 71.9])  # decorrelates the second distortion noise


def smoothstep(a, b, x):
    """Blender's Map Range (smooth step): 0 below a, 1 from b up, (3 - 2t) t^2 between."""
    a, b, x = np.broadcast_arrays(*(np.asarray(v, np.float64) for v in (a, b, x)))
    span = np.where(b > a, b - a, 1.0)
    t = np.clip((x - a) / span, 0.0, 1.0)
    return np.where(x < a, 0.0, np.where(x >= b, 1.0, t * t * (3.0 - 2.0 * t)))


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
    return noise.fbm(noise.perlin_2d, points, MAP_DETAIL).astype(np.float64)


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


def wind_direction(wind):
    """Unit horizontal wind direction; along X when calm."""
    flat = np.array([wind[0], wind[1], 0.0], np.float64)
    length = np.linalg.norm(flat)
    return flat / length if length > 1e-9 else np.array([1.0, 0.0, 0.0])


def shape_noise(points, shape_scale, seed):
    """Perlin-Worley noise at world points (..., 3): Perlin fBm dilated by inverted Worley."""
    q = np.asarray(points, np.float64) / shape_scale + seed_offset(seed)
    perlin = noise.fbm(noise.perlin_3d, q, SHAPE_DETAIL).astype(np.float64)
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


def density(points, p):
    """Cloud density (extinction per scene unit) at world points (..., 3) for parameters p, a dict:
    base, thickness, coverage, map_scale, shape_scale, detail_scale, erosion, curl, skew,
    density, precipitation, cloud_type (0..1, or None for Mixed), seed, wind, time.
    """
    points = np.asarray(points, np.float64)
    xy = (points - drift(p["wind"], p["time"]))[..., :2]
    cover = map_coverage(weather_noise(xy, p["map_scale"], p["seed"]), p["coverage"])
    cloud_type = mixed_type(xy, p["map_scale"], p["seed"]) if p["cloud_type"] is None else p["cloud_type"]
    return shaped_density(points, {**p, "cloud_type": cloud_type}, cover)


def shaped_density(points, p, cover):
    """The Cloud Density group: density at world points given the weather map's coverage there
    (p's cloud_type and precipitation stand for the map's other two channels)."""
    points = np.asarray(points, np.float64)
    carried = points - drift(p["wind"], p["time"])
    h = height_fraction(points[..., 2], p["base"], p["thickness"])
    skewed = carried - wind_direction(p["wind"]) * (p["skew"] * h)[..., None]
    shaped = shape_noise(skewed, p["shape_scale"], p["seed"]) * height_gradient(h, p["cloud_type"])
    with_cover = remap(shaped, 1.0 - cover, 1.0, 0.0, 1.0) * cover
    detail = detail_noise(skewed, p["detail_scale"], p["seed"], p["curl"], h)
    modifier = (1.0 - detail) + np.clip(10.0 * h, 0.0, 1.0) * (2.0 * detail - 1.0)
    eroded = remap(with_cover, modifier * p["erosion"], 1.0, 0.0, 1.0)
    return eroded * p["density"] * (1.0 + PRECIPITATION_GAIN * p["precipitation"])


# ---------------------------------------------------------------- phase


def henyey_greenstein(cos_theta, g):
    """HG phase per steradian: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5). (Seed 000 prints the
    1 / (4 pi) the wrong way up.)"""
    cos_theta = np.asarray(cos_theta, np.float64)
    return (1.0 - g * g) / (4.0 * math.pi * (1.0 + g * g - 2.0 * g * cos_theta) ** 1.5)


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


def frame_rays(camera, samples=17):
    """Origins and directions (world) of rays through the border of a camera's frame, and last
    the ray through its middle (a camera looking straight up sees the slab only there).

    camera: dict with "matrix" (4x4 world matrix, camera looks down its -Z), "ortho" (bool),
    and "corners": the four frame corners in camera space at z = -1 (perspective)
    or the frame half sizes (ortho: x and y of the corners, z ignored).
    """
    matrix = np.asarray(camera["matrix"], np.float64)
    corners = np.asarray(camera["corners"], np.float64)
    border = []
    for i in range(4):
        a, b = corners[i], corners[(i + 1) % 4]
        for t in np.linspace(0.0, 1.0, samples, endpoint=False):
            border.append(a + t * (b - a))
    border = np.array(border)
    rotation, location = matrix[:3, :3], matrix[:3, 3]
    if camera["ortho"]:
        flat = np.column_stack([border[:, 0], border[:, 1], np.zeros(len(border))])
        origins = flat @ rotation.T + location
        direction = rotation @ np.array([0.0, 0.0, -1.0])
        directions = np.broadcast_to(direction / np.linalg.norm(direction), origins.shape)
    else:
        origins = np.broadcast_to(location, border.shape)
        directions = border @ rotation.T
        directions = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    middle = directions.mean(axis=0)
    origins = np.vstack([origins, origins.mean(axis=0)])
    directions = np.vstack([directions, middle / np.linalg.norm(middle)])
    return origins, directions


def _slab_points(origins, directions, low, high, reach, centre):
    """Points where rays enter and leave the slab low <= z <= high, clipped to the square of
    half side reach around centre (xy); rays that miss add nothing."""
    points = []
    for origin, direction in zip(origins, directions, strict=True):
        dz = direction[2]
        if abs(dz) < 1e-12:
            if not low <= origin[2] <= high:
                continue
            spans = [0.0, math.inf]
        else:
            t0, t1 = sorted(((low - origin[2]) / dz, (high - origin[2]) / dz))
            spans = [max(t0, 0.0), t1]
            if spans[1] < spans[0]:
                continue
        # Clip the segment to the square |x - cx|, |y - cy| <= reach.
        start, end = spans
        for axis in (0, 1):
            d = direction[axis]
            lo, hi = centre[axis] - reach - origin[axis], centre[axis] + reach - origin[axis]
            if abs(d) < 1e-12:
                if not lo <= 0 <= hi:
                    start, end = 1.0, 0.0
                continue
            a, b = sorted((lo / d, hi / d))
            start, end = max(start, a), min(end, b)
        end = min(end, start + 4.0 * reach)  # a vertical ray in a horizontal slab
        if end < start:
            continue
        points.append(origin + start * direction)
        points.append(origin + end * direction)
    return np.array(points).reshape(-1, 3)


def layer_bounds(cameras, base, top, reach, ground=0.0, sun_direction=None):
    """Horizontal box (xmin, ymin, xmax, ymax) of the layer the cameras need: what they see of
    the slab base..top, and (with a sun direction, pointing at the sun) the part of the slab
    that shades the ground they see. Everything within reach of the cameras (a square).
    None when the cameras need none of it.
    """
    points = []
    for camera in cameras:
        origins, directions = frame_rays(camera)
        centre = np.asarray(camera["matrix"], np.float64)[:2, 3]
        points.append(_slab_points(origins, directions, base, top, reach, centre))
        if sun_direction is not None and sun_direction[2] > 1e-6:
            floor = ground - 1e-3 * reach  # a thin slab at the ground: where rays meet it
            seen = _slab_points(origins, directions, floor, ground, reach, centre)
            if len(seen):
                sun = np.asarray(sun_direction, np.float64) / np.linalg.norm(sun_direction)
                flat = seen.copy()
                flat[:, 2] = ground
                for height in (base, top):
                    lifted = flat + sun * ((height - ground) / sun[2])
                    lifted[:, :2] = np.clip(lifted[:, :2], centre - reach, centre + reach)
                    points.append(lifted)
    points = np.vstack([p for p in points if len(p)]) if any(len(p) for p in points) else np.zeros((0, 3))
    if not len(points):
        return None
    return (*points[:, :2].min(axis=0), *points[:, :2].max(axis=0))


def covered_cells(bounds, cells, coverage_at, spread=0.0, oversample=4):
    """Which cells of a grid over bounds (cells x cells) can hold cloud: coverage_at(xy) > 0 at
    any of oversample^2 points in the cell, dilated by spread (world units, the drift over the
    shot) plus one cell for what falls between samples. Returns a bool array (rows = y)."""
    xmin, ymin, xmax, ymax = bounds
    nx = ny = cells
    step = np.array([(xmax - xmin) / nx, (ymax - ymin) / ny])
    xs = xmin + (np.arange(nx * oversample) + 0.5) * step[0] / oversample
    ys = ymin + (np.arange(ny * oversample) + 0.5) * step[1] / oversample
    grid = np.stack(np.meshgrid(xs, ys), axis=-1)
    values = coverage_at(grid)
    hit = (values > 0).reshape(ny, oversample, nx, oversample).any(axis=(1, 3))
    reach = 1 + int(math.ceil(spread / max(min(step), 1e-12)))
    reach = min(reach, cells)
    grown = hit.copy()
    if hit.any() and reach > 0:
        padded = np.pad(hit, reach)
        for dy in range(-reach, reach + 1):
            for dx in range(-reach, reach + 1):
                grown |= padded[reach + dy:reach + dy + ny, reach + dx:reach + dx + nx]
    return grown


def column_mesh(bounds, mask, low, high):
    """Vertices and quads of one closed surface around the columns of the cells in mask
    (rows = y), from z = low to high: tops, bottoms and only the walls between a kept cell and
    a dropped one, sharing vertices so the volume is watertight."""
    ny, nx = mask.shape
    xmin, ymin, xmax, ymax = bounds
    xs = np.linspace(xmin, xmax, nx + 1)
    ys = np.linspace(ymin, ymax, ny + 1)
    index = {}
    verts = []

    def vertex(i, j, level):
        key = (i, j, level)
        if key not in index:
            index[key] = len(verts)
            verts.append((xs[i], ys[j], (low, high)[level]))
        return index[key]

    faces = []
    kept = np.pad(mask, 1)
    for j, i in zip(*np.nonzero(mask), strict=True):
        faces.append((vertex(i, j, 1), vertex(i + 1, j, 1), vertex(i + 1, j + 1, 1), vertex(i, j + 1, 1)))
        faces.append((vertex(i, j, 0), vertex(i, j + 1, 0), vertex(i + 1, j + 1, 0), vertex(i + 1, j, 0)))
        if not kept[j + 1, i]:  # west
            faces.append((vertex(i, j, 0), vertex(i, j, 1), vertex(i, j + 1, 1), vertex(i, j + 1, 0)))
        if not kept[j + 1, i + 2]:  # east
            faces.append((vertex(i + 1, j, 0), vertex(i + 1, j + 1, 0), vertex(i + 1, j + 1, 1),
                          vertex(i + 1, j, 1)))
        if not kept[j, i + 1]:  # south
            faces.append((vertex(i, j, 0), vertex(i + 1, j, 0), vertex(i + 1, j, 1), vertex(i, j, 1)))
        if not kept[j + 2, i + 1]:  # north
            faces.append((vertex(i, j + 1, 0), vertex(i, j + 1, 1), vertex(i + 1, j + 1, 1),
                          vertex(i + 1, j + 1, 0)))
    return np.array(verts, np.float64).reshape(-1, 3), faces
