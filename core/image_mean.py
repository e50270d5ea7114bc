"""An image's mean colour in scene-linear light: what a textured ground bounces on the whole.

EEVEE's light from the ground is one colour (addon/sky_eevee_ground.py); a ground whose colour
comes from an image takes the image's mean, averaged after decoding, as light adds up linearly
(the mean of sRGB codes decoded once would be darker for a contrasty texture).
"""

import numpy as np


def srgb_to_linear(codes):
    """The sRGB transfer function undone (IEC 61966-2-1), values in 0-1."""
    codes = np.clip(np.asarray(codes, dtype=np.float64), 0.0, 1.0)
    return np.where(codes <= 0.04045, codes / 12.92, ((codes + 0.055) / 1.055) ** 2.4)


CHUNK = 1 << 20  # pixels decoded at a time: a 4k image's float64 copy would be half a gigabyte


def mean_colour(pixels, channels, srgb, associated=False):
    """Mean (R, G, B) of flat pixel values (channels per pixel, RGB first), decoded from sRGB first
    when srgb. Alpha is ignored (a Base Color does not take it) unless associated: then each
    pixel's colour codes are times its alpha before decoding, as Blender premultiplies a byte
    image. Non-finite values are left out; None when no pixel is left."""
    values = np.asarray(pixels).reshape(-1, channels)
    total, count = np.zeros(3), 0
    for start in range(0, len(values), CHUNK):
        chunk = values[start:start + CHUNK].astype(np.float64)
        rgb = np.repeat(chunk[:, :1], 3, axis=1) if channels < 3 else chunk[:, :3]  # grey: R = G = B
        if associated and channels == 4:
            rgb = rgb * chunk[:, 3:4]
        rgb = rgb[np.all(np.isfinite(rgb), axis=1)]
        total += (srgb_to_linear(rgb) if srgb else rgb).sum(axis=0)
        count += len(rgb)
    if count == 0:
        return None
    return tuple(float(v) for v in np.maximum(total / count, 0.0))
