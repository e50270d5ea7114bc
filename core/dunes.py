"""Wind-shaped dunes as a numpy height field.

Transverse dunes under a wind blowing along +X: a long, gentle windward (stoss) slope up to
a crest, then a short lee slip face no steeper than sand's angle of repose (about 33
degrees). Crest lines meander across the wind and their height varies; wind ripples
(centimetres, a few per metre, across the wind) ride on top.
"""

import numpy as np

REPOSE_DEGREES = 33.0


def dune_heights(x, y, wavelength=18.0, height=1.8, crest=0.8, meander=3.0, meander_length=30.0,
                 ripple_height=0.02, ripple_length=0.35, seed=0):
    """Height in metres at (x, y) metres; vectorised over any array shape.

    wavelength: dune spacing along the wind; crest: where the crest sits in each period
    (0.8 = windward slope four times longer than the lee); meander: sideways crest wander.
    """
    rng = np.random.default_rng(seed)
    phase_a, phase_b = rng.uniform(0, 2 * np.pi, 2)
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    wander = meander * np.sin(2 * np.pi * y / meander_length + phase_a)
    s = np.mod((x + wander) / wavelength, 1.0)  # 0 at a trough, `crest` at the crest
    stoss = s / crest
    lee = (1.0 - s) / (1.0 - crest)
    # Smooth rise (sin^2 ease-in) on the windward side; a straight slip face on the lee.
    profile = np.where(s < crest, np.sin(0.5 * np.pi * stoss) ** 2, lee)
    amplitude = height * (0.75 + 0.25 * np.sin(2 * np.pi * y / (1.7 * meander_length) + phase_b))
    ripples = ripple_height * np.sin(2 * np.pi * (x + 0.3 * wander) / ripple_length)
    return amplitude * profile + ripples * (0.3 + 0.7 * profile)


def max_lee_slope_degrees(wavelength=18.0, height=1.8, crest=0.8):
    """Steepest slip face the parameters give (without ripples), in degrees."""
    return float(np.degrees(np.arctan(height / ((1.0 - crest) * wavelength))))


def grid(size_x, size_y, spacing, **dune):
    """Vertices (N, 3) and quads (M, 4) of a dune height field centred on the origin."""
    nx = max(int(round(size_x / spacing)), 1)
    ny = max(int(round(size_y / spacing)), 1)
    xs = np.linspace(-size_x / 2, size_x / 2, nx + 1)
    ys = np.linspace(-size_y / 2, size_y / 2, ny + 1)
    x, y = np.meshgrid(xs, ys)
    z = dune_heights(x, y, **dune)
    index = np.arange((nx + 1) * (ny + 1)).reshape(ny + 1, nx + 1)
    quads = np.stack([index[:-1, :-1], index[:-1, 1:], index[1:, 1:], index[1:, :-1]], -1).reshape(-1, 4)
    return np.stack([x, y, z], -1).reshape(-1, 3), quads
