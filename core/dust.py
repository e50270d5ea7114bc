"""Wind-lifted dust in plain numpy: the twin of node group "Sandscape Dust Field".

Dust is a 2D noise field over the ground carried by the wind (sampled at position - wind x time),
thresholded into clear and dusty patches with soft edges, and thinning with height above the
ground as exp(-height / falloff).
"""

import numpy as np

from . import noise_perlin
from .shaping import smoothstep

NOISE_DETAIL = 3.0  # the group's Noise Texture: Detail 3, roughness 0.5, lacunarity 2, 2D


def dust_field(position, frame, fps, wind, scale, coverage, softness, ground, falloff):
    """Dust density factor 0..1 at world positions (..., 3)."""
    position = np.asarray(position, np.float64)
    time = frame / fps
    carried = position - np.asarray(wind, np.float64) * time
    noise = noise_perlin.fbm(noise_perlin.perlin_2d, carried[..., :2] * (1.0 / scale), NOISE_DETAIL)
    edge = 1.0 - coverage
    patches = smoothstep(edge - softness, edge + softness, noise)
    height = np.maximum(position[..., 2] - ground, 0.0)
    return patches * np.exp(-height / falloff)
