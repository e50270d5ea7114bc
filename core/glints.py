"""Numpy twins of the glint node groups, in float32 like Cycles.

glint_shade   <-> node group "Sandscape Glint Shade"
sparkle_cells <-> node group "Sandscape Glint Cells" (cells sized to the pixel's footprint)
glints        <-> node group "Sandscape Glints" (sparkle cells + shade)
noise_image / sample_nearest <-> the image source (an Image Texture, Closest, Repeat)
"""

import numpy as np

from .noise_hash import white_noise_4d, white_noise_4d_color

F32 = np.float32


def _safe_divide(a, b):
    # Cycles' Vector Math Divide returns 0 where the divisor is 0.
    b = np.asarray(b, dtype=F32)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(b != 0, np.asarray(a, dtype=F32) / np.where(b != 0, b, F32(1)), F32(0))


def cell_noise(position, size, seed):
    """Per-cell white noise: floor(position / size + 0.5) hashed with the seed as 4th dimension.

    The + 0.5 centres cells on multiples of the size, so a surface at z = 0 sits mid-cell.
    """
    cell = np.floor(_safe_divide(position, size) + F32(0.5)).astype(F32)
    return white_noise_4d(cell, F32(seed))


# A sparkle's cell spans from SPARKLE_CELL to twice that of the pixel's footprint on the surface,
# so a sparkle covers at most one pixel; its edge is Glint Size x 2^level, level within LEVELS.
SPARKLE_CELL = 0.5
LEVELS = (-6, 12)
LEVEL_SEED = 37.0  # each level hashes with Seed + LEVEL_SEED x level: its own set of sparkles


def sparkle_level(footprint, size):
    """The level of the sparkle cells: ceil(log2(SPARKLE_CELL x footprint / size)) within LEVELS,
    0 where there is no footprint (no camera: one cell per grain, as before filtering)."""
    footprint = np.asarray(footprint, F32)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(footprint > 0, SPARKLE_CELL * footprint / F32(size), F32(1))
        level = np.ceil(np.log2(np.maximum(ratio, F32(1e-30)))).astype(F32)
    return np.clip(level, *LEVELS).astype(F32)


MIN_FACING = 0.05  # N.V below this counts as this: a grazing pixel's footprint stops growing


def level_threshold(threshold, grains):
    """The threshold of a cell of `grains` grains: a coarse cell sparkles when one of its grains
    would (threshold^grains), a fine one keeps the grains' count per area (1 - grains (1 -
    threshold)); the larger is the level's, and they meet at one grain."""
    return np.maximum(np.power(threshold, grains), 1 - (1 - threshold) * grains)


def sparkle_cells(footprint, size, threshold, n_dot_v=1.0):
    """(cell size, threshold, weight) of the sparkle cells for a pixel footprint (object units)
    where the view meets the surface at n_dot_v.

    A cell of 2^level grains on a side holds a = 4^level of them. A coarse cell (level >= 0)
    sparkles when one of its grains would: noise above threshold^a; its weight (its grains'
    share of the light, (1 - threshold) / (1 - threshold^a), at most 1) keeps the sand's mean.
    A fine cell (level < 0) keeps a grain's count per area, a (1 - threshold) of the cells, and
    carries the grain's light into its one pixel: weight 4^-level, but no brighter than a whole
    pixel of mirror (the pixel's area on the surface, footprint^2 / N.V, over the cell's). The
    larger of the two thresholds is each level's; both weights are 1 at level 0.
    """
    level = sparkle_level(footprint, size)
    grains = np.power(F32(4), level).astype(F32)
    threshold = F32(threshold)
    cell_threshold = level_threshold(threshold, grains)
    share = _safe_divide(F32(1) - threshold, F32(1) - cell_threshold)
    cell_size = (F32(size) * np.power(F32(2), level)).astype(F32)
    facing = np.maximum(np.abs(np.asarray(n_dot_v, F32)), F32(MIN_FACING))
    footprint = np.asarray(footprint, F32)
    pixel_cells = _safe_divide(footprint * footprint, cell_size * cell_size * facing)
    pixel_cells = np.maximum(pixel_cells, (level >= 0).astype(F32))  # coarse cells: the share alone
    return cell_size, cell_threshold, np.minimum(share, pixel_cells).astype(F32)


def sparkle_noise(position, footprint, size, threshold, seed, n_dot_v=1.0):
    """(noise, tilt, threshold, weight) per point: the sparkle cell's noise and tilt colour at its
    level, and the level's threshold and weight."""
    cell_size, cell_threshold, weight = sparkle_cells(footprint, size, threshold, n_dot_v)
    level = sparkle_level(footprint, size)
    cell = np.floor(_safe_divide(position, cell_size[..., None]) + F32(0.5)).astype(F32)
    w = (F32(seed) + F32(LEVEL_SEED) * level).astype(F32)
    return white_noise_4d(cell, w), white_noise_4d_color(cell, w), cell_threshold, weight


def glint_shade(noise, n_dot_v, threshold, power, color, strength):
    """Returns (mask, glint_color): mask = [noise > threshold] * (N·V)^max(power, 0)."""
    lit = (np.asarray(noise, F32) > F32(threshold)).astype(F32)
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        falloff = np.power(np.asarray(n_dot_v, F32), F32(max(power, 0.0)))
    mask = lit * falloff
    scaled = mask * F32(strength)
    glint_color = scaled[..., None] * np.asarray(color, F32)[:3]
    return mask, glint_color


def glints(position, n_dot_v, threshold, size, power, color, strength, seed, footprint=0.0):
    """Twin of the Sandscape Glints group at object-space positions (..., 3); footprint: the
    pixel's footprint there in object units (0: one cell per grain)."""
    footprint = np.broadcast_to(np.asarray(footprint, F32), np.shape(position)[:-1])
    noise, _, cell_threshold, weight = sparkle_noise(position, footprint, size, threshold, seed, n_dot_v)
    mask = (noise > cell_threshold).astype(F32) * weight
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        mask = mask * np.power(np.asarray(n_dot_v, F32), F32(max(power, 0.0)))
    return mask, (mask * F32(strength))[..., None] * np.asarray(color, F32)[:3]


def noise_image(resolution, seed):
    """A seeded white-noise image: uniform 8-bit values, so the threshold still sets how many glint.

    The seed paper's image held only 0 and 1, which makes every threshold below 1 light half
    of the texels; uniform values keep the threshold meaningful (lit ≈ 1 - threshold, in
    steps of 1/255).
    """
    rng = np.random.default_rng(seed)
    return rng.integers(0, 256, size=(resolution, resolution), dtype=np.uint8)


def byte_to_unit(values):
    return np.asarray(values, F32) * F32(1.0 / 255.0)


def sample_nearest(image, uv):
    """Closest-texel lookup with Repeat extension; image rows go bottom to top like Blender's."""
    height, width = image.shape[:2]
    uv = np.asarray(uv, F32)
    ix = np.floor(uv[..., 0] * F32(width)).astype(np.int64) % width
    iy = np.floor(uv[..., 1] * F32(height)).astype(np.int64) % height
    return byte_to_unit(image[iy, ix])
