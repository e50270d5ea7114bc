"""Small shaping functions several models share, written once: Blender's smooth step, the
Henyey-Greenstein phase and the wind's horizontal direction."""

import math

import numpy as np


def smoothstep(a, b, x):
    """Blender's Map Range (smooth step): 0 below a, 1 from b up, (3 - 2t) t^2 between; a step at
    a when a == b."""
    a, b, x = np.broadcast_arrays(*(np.asarray(v, np.float64) for v in (a, b, x)))
    span = np.where(b > a, b - a, 1.0)
    t = np.clip((x - a) / span, 0.0, 1.0)
    return np.where(x < a, 0.0, np.where(x >= b, 1.0, t * t * (3.0 - 2.0 * t)))


def henyey_greenstein(cos_theta, g):
    """HG phase per steradian: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5), |g| < 1. (Seed 000
    prints the 1 / (4 pi) the wrong way up.)"""
    cos_theta = np.asarray(cos_theta, np.float64)
    return (1.0 - g * g) / (4.0 * math.pi * (1.0 + g * g - 2.0 * g * cos_theta) ** 1.5)


def wind_direction(wind):
    """Unit horizontal wind direction (x, y, 0); along X when calm."""
    flat = np.array([wind[0], wind[1], 0.0], np.float64)
    length = np.linalg.norm(flat)
    return flat / length if length > 1e-9 else np.array([1.0, 0.0, 0.0])
