"""How a frame reads to an artist's eye: hue and saturation of display values (shared by
bench/effects.py and tests/test_sand_colour.py)."""

import numpy as np


def hue_saturation(rgb):
    """HSV hue in degrees and saturation of display RGB in 0..1, vectorised."""
    high, low = rgb.max(axis=-1), rgb.min(axis=-1)
    span = np.where(high > low, high - low, 1.0)
    r, g, b = np.moveaxis(rgb, -1, 0)
    hue = np.where(high == r, (g - b) / span % 6.0,
                   np.where(high == g, (b - r) / span + 2.0, (r - g) / span + 4.0))
    hue = np.where(high > low, hue * 60.0, 0.0)
    saturation = np.where(high > 0, (high - low) / np.where(high > 0, high, 1.0), 0.0)
    return hue, saturation


def lit_lower_half(pixels):
    """Median hue and saturation of the lower half's brighter half (rows bottom-up: the first half)."""
    lower = pixels[: pixels.shape[0] // 2, :, :3].reshape(-1, 3)
    value = lower.max(axis=-1)
    lit = lower[value >= np.median(value)]
    hue, saturation = hue_saturation(lit)
    return float(np.median(hue)), float(np.median(saturation))
