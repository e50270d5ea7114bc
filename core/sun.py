"""The sun that matches the sky: the lamp's strength and colour, and the exposure to propose,
from the sky model's own sun (core/sun_table.py, measured in Blender).

Irradiances are in Blender's light units (a sun lamp's strength: W/m² on a surface facing it).
Between the measured elevations the table is interpolated linearly; below the horizon the disc
gives nothing.
"""

import numpy as np

from . import sun_table

_TABLE = np.array(sun_table.ROWS, dtype=np.float64)
_DEGREES, _DISC, _SKY = _TABLE[:, 0], _TABLE[:, 1:4], _TABLE[:, 4:7]
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec. 709, Blender's linear scene luminance


def _interpolate(elevation, columns):
    degrees = np.clip(np.degrees(float(elevation)), _DEGREES[0], _DEGREES[-1])
    return np.array([np.interp(degrees, _DEGREES, column) for column in columns.T])


def disc_irradiance(elevation):
    """The sun's irradiance on a surface facing it, (R, G, B), at a sun elevation in radians."""
    return np.maximum(_interpolate(elevation, _DISC), 0.0)


def disc_solid_angle(size):
    """Solid angle (sr) of a disc `size` radians across."""
    return 2.0 * np.pi * (1.0 - np.cos(0.5 * float(size)))


def disc_radiance(irradiance, size):
    """Radiance of an even disc `size` radians across that gives `irradiance` on a surface facing it."""
    return np.asarray(irradiance, dtype=np.float64) / disc_solid_angle(size)


def sky_irradiance(elevation):
    """The disc-less sky's irradiance on level ground, (R, G, B)."""
    return _interpolate(elevation, _SKY)


def sky_rows():
    """The table's (elevations in degrees, sky irradiance on level ground (R, G, B) per row)."""
    return _DEGREES.copy(), _SKY.copy()


def lamp(elevation):
    """(strength, colour) of a sun lamp that lights like the sky's sun: colour's largest channel 1."""
    rgb = disc_irradiance(elevation)
    strength = float(rgb.max())
    if strength <= 0.0:
        return 0.0, (1.0, 1.0, 1.0)
    return strength, tuple(float(c) for c in rgb / strength)


def level_irradiance(elevation):
    """(direct, sky) irradiance on level ground, each (R, G, B)."""
    direct = disc_irradiance(elevation) * max(np.sin(float(elevation)), 0.0)
    return direct, sky_irradiance(elevation)


def exposure(elevation, lamp=None, sky=True):
    """The exposure (stops) at which level grey ground under this sun and sky reads as its own
    albedo: its radiance is albedo x E / pi, so the exposure is log2(pi / E) in luminance.

    lamp: (strength, colour) of the sun lamp when it is not the sky model's own sun (an artist's,
    at strength 4, is some forty times dimmer); sky: False where the sky model does not light the
    ground (the artist's own world, whose light is not known here, is left out)."""
    direct, sky_light = level_irradiance(elevation)
    if lamp is not None:
        direct = lamp[0] * np.asarray(lamp[1], dtype=np.float64)[:3] * max(np.sin(float(elevation)), 0.0)
    total = float((direct + (sky_light if sky else 0.0)) @ LUMINANCE)
    return float(np.log2(np.pi / max(total, 1e-6)))
