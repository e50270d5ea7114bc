"""Numpy twins of the glint node groups, in float32 like Cycles.

glint_shade  <-> node group "Sandscape Glint Shade"
glints       <-> node group "Sandscape Glints" (object-space cells + shade)
noise_image / sample_nearest <-> the image source (an Image Texture, Closest, Repeat)
"""

import numpy as np

from .noise_hash import white_noise_4d

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


def glint_shade(noise, n_dot_v, threshold, power, color, strength):
    """Returns (mask, glint_color): mask = [noise > threshold] * (N·V)^max(power, 0)."""
    lit = (np.asarray(noise, F32) > F32(threshold)).astype(F32)
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        falloff = np.power(np.asarray(n_dot_v, F32), F32(max(power, 0.0)))
    mask = lit * falloff
    scaled = mask * F32(strength)
    glint_color = scaled[..., None] * np.asarray(color, F32)[:3]
    return mask, glint_color


def glints(position, n_dot_v, threshold, size, power, color, strength, seed):
    """Twin of the Sandscape Glints group at object-space positions (..., 3)."""
    return glint_shade(cell_noise(position, size, seed), n_dot_v, threshold, power, color, strength)


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
