"""The cloud layer's shadow as EEVEE can cast it. EEVEE's volumes shadow no surface, so a layer of
the clouds' own light-let-through is laid at their base: for each point of the base, the light
that crosses the layer towards the sun, exp(-optical depth along the sun's ray), outlined where
under half gets through into a mesh that only shadow rays see (addon/cloud_shadows.py). Cycles
shadows the ground through the volume itself.
"""

import numpy as np

MAX_TEXELS = 192  # along the longer side of the layer's box: the shadows' edges blur over a texel
MAX_STEPS = 48  # along the sun's ray through the layer (a 6-degree sun's crosses 10 thicknesses)
LOWEST_SINE = float(np.sin(np.radians(0.5)))  # a lower sun's ray is stepped as if it stood this high
# The higher orders of scattering as octaves (Wrenninge 2015): order i sees the extinction and
# scatters the light each scaled by OCTAVE_SCALE^i.
OCTAVES, OCTAVE_SCALE = 3, 0.5


def unit(vector):
    vector = np.asarray(vector, np.float64)
    return vector / np.linalg.norm(vector)


def texel_centres(box, texels=MAX_TEXELS):
    """x and y of the texel centres over box (xmin, ymin, xmax, ymax), rows = y: square-ish
    texels, `texels` along the longer side."""
    xmin, ymin, xmax, ymax = box
    width, depth = xmax - xmin, ymax - ymin
    columns = max(2, int(round(texels * min(1.0, width / depth))))
    rows = max(2, int(round(texels * min(1.0, depth / width))))
    return np.meshgrid(*_axes(box, rows, columns))


def _axes(box, rows, columns):
    """The x of each column's and the y of each row's texel centre over box."""
    xmin, ymin, xmax, ymax = box
    return (xmin + (np.arange(columns) + 0.5) * (xmax - xmin) / columns,
            ymin + (np.arange(rows) + 0.5) * (ymax - ymin) / rows)


def steps_for(thickness, to_sun, step):
    """Ray-marching steps through the layer towards the sun: `step` long, at most MAX_STEPS."""
    length = thickness / unit(to_sun)[2]
    return int(min(max(np.ceil(length / max(step, 1e-9)), 1), MAX_STEPS))


def transmittance(density_at, box, base, thickness, to_sun, steps, texels=MAX_TEXELS):
    """exp(-optical depth) from each texel of the layer's base (rows = y) towards the sun, through
    `thickness` of the density density_at(points (..., 3)) (extinction per unit length): midpoint
    steps along the ray. The sun must be above the horizon."""
    to_sun = unit(to_sun)
    if to_sun[2] <= 0.0:
        raise ValueError("the sun is not above the horizon: the layer casts no shadow")
    xs, ys = texel_centres(box, texels)
    length = thickness / to_sun[2]
    step = length / steps
    depth = np.zeros_like(xs)
    for k in range(steps):
        t = (k + 0.5) * step
        points = np.stack([xs + to_sun[0] * t, ys + to_sun[1] * t, np.full_like(xs, base + to_sun[2] * t)],
                          axis=-1)
        depth += np.asarray(density_at(points), np.float64) * step
    return np.exp(-depth)


def voxel_transmittance(cloudiness, corner, voxel, to_sun, thickness, steps, density, wet):
    """exp(-optical depth) from each voxel's centre (cloudiness (nx, ny, nz) at corner + index x
    voxel) towards the sun, as the cloud grid bakes it (addon/cloud_sunlight.py): `steps`
    midpoint steps of thickness / sin(elevation) / steps along the ray, the extinction
    clamp(cloudiness interpolated, 0, wet) x density, none outside the grid."""
    to_sun = unit(to_sun)
    across = thickness / steps / max(to_sun[2], LOWEST_SINE)
    shape = np.shape(cloudiness)
    centres = np.stack(np.meshgrid(*[corner[axis] + np.arange(shape[axis]) * voxel for axis in range(3)],
                                   indexing="ij"), axis=-1)
    depth = np.zeros(shape)
    for k in range(steps):
        points = centres + to_sun * (k + 0.5) * across
        depth += np.clip(trilinear(cloudiness, corner, voxel, points), 0.0, wet)
    return np.exp(-depth * across * density)


def many_scatterings(let_through, octaves=OCTAVES, scale=OCTAVE_SCALE):
    """The sun's light the second to last orders of scattering bring a voxel, as a share of the
    lamp's, from T the light let through to it: the sum over i = 1..octaves of scale^i x
    T^(scale^i) (extinction scaled by scale^i: exp(-scale^i tau)). Their lobes flatten with each
    order: taken isotropic."""
    t = np.clip(np.asarray(let_through, np.float64), 0.0, 1.0)
    return sum(scale ** i * t ** (scale ** i) for i in range(1, octaves + 1))


def trilinear(values, corner, voxel, points):
    """values (nx, ny, nz), sampled at corner + index x voxel, interpolated at points (..., 3) as a
    volume grid is: none outside the grid's box."""
    values = np.asarray(values, np.float64)
    shape = np.array(values.shape)
    where = (np.asarray(points, np.float64) - np.asarray(corner, np.float64)) / voxel
    inside = np.all((where >= 0.0) & (where <= shape - 1), axis=-1)
    where = np.clip(where, 0.0, shape - 1)
    low = np.minimum(np.floor(where).astype(int), shape - 2)
    frac = where - low
    total = np.zeros(where.shape[:-1])
    for corner_index in np.ndindex(2, 2, 2):
        weight = np.ones(where.shape[:-1])
        for axis, side in enumerate(corner_index):
            weight = weight * (frac[..., axis] if side else 1.0 - frac[..., axis])
        i, j, k = (low[..., axis] + side for axis, side in enumerate(corner_index))
        total += weight * values[i, j, k]
    return np.where(inside, total, 0.0)


def shadow_polygons(light, box, threshold=0.5):
    """The ground the map shades, as polygons: marching squares over the texel centres of `light`
    (rows = y) spanning box, each cell cut where its corners cross `threshold` (linearly between
    them). Returns (vertices (n, 2), polygons: lists of vertex indices, counter-clockwise)."""
    light = np.asarray(light, np.float64)
    xs, ys = _axes(box, *light.shape)
    inside = light < threshold
    corners = ((0, 0), (0, 1), (1, 1), (1, 0))  # (row, column) offsets, counter-clockwise in x-y
    vertices, polygons = [], []
    cells = np.argwhere(inside[:-1, :-1] | inside[1:, :-1] | inside[:-1, 1:] | inside[1:, 1:])
    for i, j in cells:
        polygon = []
        for k in range(4):
            (ai, aj), (bi, bj) = corners[k], corners[(k + 1) % 4]
            a, b = light[i + ai, j + aj], light[i + bi, j + bj]
            if a < threshold:
                polygon.append((xs[j + aj], ys[i + ai]))
            if (a < threshold) != (b < threshold):
                t = (threshold - a) / (b - a)
                x, y = xs[j + aj], ys[i + ai]
                polygon.append((x + t * (xs[j + bj] - x), y + t * (ys[i + bi] - y)))
        if len(polygon) >= 3:
            polygons.append(list(range(len(vertices), len(vertices) + len(polygon))))
            vertices.extend(polygon)
    return np.array(vertices, np.float64).reshape(-1, 2), polygons


def smoothed(light):
    """The map blurred by a [1, 2, 1] / 4 kernel along each axis (edges repeated): rounder
    outlines than the texels' straight cuts."""
    light = np.asarray(light, np.float64)
    for axis in (0, 1):
        padded = np.pad(light, [(1, 1) if a == axis else (0, 0) for a in (0, 1)], mode="edge")
        low, mid, high = (np.take(padded, np.arange(k, k + light.shape[axis]), axis=axis) for k in range(3))
        light = 0.25 * low + 0.5 * mid + 0.25 * high
    return light
