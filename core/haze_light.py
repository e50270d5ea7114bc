"""Sunlight the haze scatters down onto the ground: the warm half of the shade's light.

Cycles renders the dust box's haze scattering the lamp's light in every direction, and part of it
lights the sand from the sky around the sun: with a low sun that light (the lamp's colour) is a
large share of what shaded sand gets beside the blue sky's. EEVEE's volumes light no surface,
so its lighting world adds this light to the sky's, from where it comes (addon/sky_eevee_haze.py).

Single scattering in a box of uniform haze seen from its floor's centre: the floor at height 0,
the top at `height`, the sides a cylinder of `radius` (the box's half-width) about the point.
Our box never shadows the lamp (addon/atmosphere.py), so the sun reaches every point of the haze
undimmed. Multiple scattering is left out. Checked against Cycles renders (tests/test_haze_light.py).
"""

import numpy as np

from .atmosphere import henyey_greenstein

# Quadrature: steps in the sine of the elevation (finer near the horizon, where a low sun's
# forward lobe lies) and in azimuth.
ELEVATION_STEPS, AZIMUTH_STEPS = 256, 256


def radiance(directions, to_sun, extinction, anisotropy, height, radius):
    """Radiance of the haze towards the ground's centre from unit directions above it (..., 3),
    per unit of the sun's irradiance (on a surface facing it): the sun's light the phase turns
    down each ray, times the share of it that scatters within the box on the way in,
    1 - exp(-extinction x reach), reach the ray's length to the box's top or side. Below the
    horizon none. The world's EEVEE output holds the same in nodes (addon/sky_eevee_haze.py)."""
    directions = np.asarray(directions, np.float64)
    up = directions[..., 2]
    flat = np.sqrt(np.maximum(1.0 - up * up, 0.0))
    reach = np.minimum(height / np.maximum(up, 1e-12), radius / np.maximum(flat, 1e-12))
    scattered = -np.expm1(-extinction * reach)
    return np.where(up > 0, henyey_greenstein(directions @ np.asarray(to_sun, np.float64), anisotropy)
                    * scattered, 0.0)


def scattered_irradiance(extinction, anisotropy, height, radius, sine_elevation):
    """Irradiance on level ground from haze-scattered sunlight per unit of the sun's irradiance
    (on a surface facing it): extinction per unit length (all of it scattering), the
    Henyey-Greenstein anisotropy, the haze's height over the ground and its half-width. The
    integral of radiance() times the cosine over the sky."""
    sine = float(np.clip(sine_elevation, 0.0, 1.0))
    if not (extinction > 0 and height > 0 and radius > 0 and sine > 0):
        return 0.0
    to_sun = np.array([np.sqrt(1.0 - sine * sine), 0.0, sine])
    t = (np.arange(ELEVATION_STEPS) + 0.5) / ELEVATION_STEPS
    up, d_up = t * t, 2.0 * t / ELEVATION_STEPS  # u = sin(elevation) = t^2
    phi = (np.arange(AZIMUTH_STEPS) + 0.5) / AZIMUTH_STEPS * 2.0 * np.pi
    flat = np.sqrt(1.0 - up * up)[:, None]
    directions = np.stack([flat * np.cos(phi), flat * np.sin(phi), up[:, None] * np.ones_like(phi)], -1)
    light = radiance(directions, to_sun, extinction, anisotropy, height, radius)
    return float(np.sum(light * (up * d_up)[:, None]) * 2.0 * np.pi / AZIMUTH_STEPS)
