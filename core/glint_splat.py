"""Numpy twin of Sandscape Glint Splat: sparkles as points jittered in the cells of the object's
lattice, each put into the pixels round the point where it projects, shared by a smoothstep tent of
one pixel.

pixel_amounts gathers, for every pixel, the lattice points near its centre at the pixel's level and
weighs them by where they project: the exact projection the caller gives (the node group uses the
pixel's footprint, a linear one, and four candidates), so it is a reference, not a copy.
"""

import numpy as np

from . import glints
from .noise_hash import white_noise_4d, white_noise_4d_color

CANDIDATES = (1, 2, 3, 4)
OFFSETS = ((0, 0), (1, 0), (0, 1), (1, 1))  # from the first cell that can reach the pixel
MIN_DEPTH = 1e-6
MIN_FACING = 1e-4  # |N·ray| of the centre's ray (unit depth) below this counts as this
# A point's light goes to its pixel alone while it lies within (1 − SHARE_WIDTH) / 2 of the centre,
# and passes to the neighbour by a smoothstep over SHARE_WIDTH pixels round the edge: a sparkle is
# one pixel most of the time yet glides, not jumps, when it crosses.
SHARE_WIDTH = 0.5
# Each cell's point is jittered round its lattice point (a jittered grid): points at the lattice
# points lined up, and where nearly every coarse cell glints (a shaded slope mirroring the sky) they
# beat with the pixels into a lattice of specks about 7 px apart (the twelfth review). JITTER is the
# spread's width in cells. A point TENT_REACH pixels or more from the centre along either screen
# axis gives the pixel nothing, so cells of at least CELL_REACH x the pixel's reach (one pixel each
# way) leave at most two per axis that can reach it: four candidates. A spread of a whole cell needs
# cells 1.5x the reach, and the one-pixel bound then loses 11 % of the light at eye height (0.75: 5 %,
# none: 3 %; the twin on the scene of tests/test_glint_splat.py).
JITTER = 0.75
JITTER_SEED = 101.0  # the jitter hashes the cell with the level's seed + this (its tilt takes the seed)
TENT_REACH = 0.5 + SHARE_WIDTH / 2
CELL_REACH = 2.0 * TENT_REACH / (2.0 - JITTER)


def tent(offset):
    """A pixel's share of a point `offset` pixels from its centre along one axis. The shares of two
    neighbours sum to one, so a point's light is kept wherever it lies."""
    low = 0.5 - SHARE_WIDTH / 2
    x = np.clip((np.abs(np.asarray(offset, np.float64)) - low) / SHARE_WIDTH, 0.0, 1.0)
    return 1.0 - x * x * (3.0 - 2.0 * x)


def lattice_axes(normal):
    """(first, second, normal) axis of the object's lattice for a unit normal: the plane the normal
    leans least from (z wins ties, then x), as (..., 3) index arrays."""
    lean = np.abs(np.asarray(normal, np.float64))
    z_up = lean[..., 2] >= np.maximum(lean[..., 0], lean[..., 1])
    x_up = ~z_up & (lean[..., 0] >= lean[..., 1])
    axes = np.where(z_up[..., None], (0, 1, 2), np.where(x_up[..., None], (1, 2, 0), (2, 0, 1)))
    code = np.where(z_up, 0.0, np.where(x_up, 1.0, 2.0))
    return axes, code


def cells(reach, size, threshold, rise, pixel_area):
    """(cell size, level, the level's threshold, mirror share of the pixel) for a pixel whose reach on
    the lattice is `reach` (one pixel each way), `rise` the normal's part on the lattice's axis and
    `pixel_area` the pixel's area on the surface."""
    reach = np.asarray(reach, np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        level = np.ceil(np.log2(np.maximum(CELL_REACH * reach / size, 1e-30)))
    level = np.clip(level, *glints.LEVELS)
    grains = 4.0 ** level
    level_threshold = glints.level_threshold(threshold, grains)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.where(level_threshold < 1.0, (1.0 - threshold) / (1.0 - level_threshold), 0.0)
    cell = size * 2.0 ** level
    mirror = np.minimum(share * cell * cell / np.maximum(rise, 1e-6) / pixel_area, 1.0)
    return cell, level, level_threshold, mirror


def pixel_amounts(centres, step_u, step_v, normals, project, size, threshold, seed, search=2):
    """Share of each pixel that is glinting mirror: (H, W) from per-pixel arrays (H, W, 3) of the
    centre's point on the surface, the surface steps for one pixel across and up, and the unit normal,
    all in the object's space. project(points (..., 3)) -> (columns, rows) in pixels, exact, measured
    so that a pixel's centre is at +0.5. Lattice points within `search` cells of the centre count."""
    height, width = centres.shape[:2]
    axes, code = lattice_axes(normals)
    take = np.take_along_axis
    ca, cb = take(centres, axes[..., :1], -1)[..., 0], take(centres, axes[..., 1:2], -1)[..., 0]
    ua, ub = take(step_u, axes[..., :1], -1)[..., 0], take(step_u, axes[..., 1:2], -1)[..., 0]
    va, vb = take(step_v, axes[..., :1], -1)[..., 0], take(step_v, axes[..., 1:2], -1)[..., 0]
    rise = np.abs(take(normals, axes[..., 2:], -1)[..., 0])
    reach = np.maximum(np.abs(ua) + np.abs(va), np.abs(ub) + np.abs(vb))
    area = np.linalg.norm(np.cross(step_u, step_v), axis=-1)
    cell, level, level_threshold, mirror = cells(reach, size, threshold, rise, area)
    rows, columns = np.mgrid[0:height, 0:width]
    total = np.zeros((height, width))
    for di in range(-search, search + 1):
        for dj in range(-search, search + 1):
            i = np.round(ca / cell) + di
            j = np.round(cb / cell) + dj
            point = np.array(centres, np.float64)
            cell_index = np.stack([i, j, code], -1).astype(np.float32)
            level_seed = (seed + glints.LEVEL_SEED * level).astype(np.float32)
            jitter = white_noise_4d_color(cell_index, level_seed + np.float32(JITTER_SEED))[..., :2] - 0.5
            lattice = (np.stack([i, j], -1) + JITTER * jitter) * cell[..., None]
            np.put_along_axis(point, axes[..., :1], lattice[..., :1], -1)
            np.put_along_axis(point, axes[..., 1:2], lattice[..., 1:], -1)
            # On the tangent plane, straight along the lattice's normal axis.
            n = np.asarray(normals, np.float64)
            along = take(n, axes[..., 2:], -1)[..., 0]
            lift = np.sum(n * (point - centres), -1) / np.where(rise > 0, along, 1)
            np.put_along_axis(point, axes[..., 2:], take(point, axes[..., 2:], -1) - lift[..., None], -1)
            u, v = project(point)
            weight = tent(u - (columns + 0.5)) * tent(v - (rows + 0.5))
            noise = white_noise_4d(cell_index, level_seed)
            total += weight * (noise > level_threshold) * mirror
    return total / np.maximum(total, 1.0)


def splat(points, amounts, width, height):
    """Each point's amount put into the pixels round it (columns, rows in pixels, centres at +0.5):
    the image a perfect splat makes, for the mean light."""
    image = np.zeros((height, width))
    u, v = points
    for du in (-1, 0, 1):
        for dv in (-1, 0, 1):
            col, row = np.floor(u).astype(int) + du, np.floor(v).astype(int) + dv
            inside = (col >= 0) & (col < width) & (row >= 0) & (row < height)
            weight = tent(u - (col + 0.5)) * tent(v - (row + 0.5)) * amounts
            np.add.at(image, (row[inside], col[inside]), weight[inside])
    return image
