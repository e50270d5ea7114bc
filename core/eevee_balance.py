"""The factor that brings our Physical Sand in EEVEE to Cycles' brightness, as a function of the
view, the sun and the surface: the twin of "Sandscape EEVEE Balance".

EEVEE has neither Cycles' rough (Oren-Nayar) diffuse nor its microfiber sheen: its diffuse is
Lambert and its sheen is lit like a diffuse. Under a low sun Cycles' sand is up to 3.7x brighter
seen with the sun behind (back-scatter at grazing angles), and under a high sun EEVEE's is
brighter. With C = Cycles' brightness over EEVEE's, the balance G is C where C < 1 (the EEVEE
output scales its surface by it) and 1 + (C − 1) E / D above (it adds G − 1 of the sun's light
on a Lambert diffuse of the sand's colour, D, below the sand's E: the sky's light is left as it
is). C and E were measured on a flat plane of the sand under our sun and sky, D under the sun
alone (devtools/eevee_balance_data.py), and G fitted here as exp(polynomial) in

    v = N·V, l = N·L (each at least MIN_COSINE) and a = cos of the azimuth between V and L
    about N (a = 1: the sun in front of the camera; -1: behind it).

The fit is a calibration, not physics; its reference is Cycles itself (bench/eevee.py measures
an EEVEE frame against a Cycles one).
"""

import itertools

import numpy as np

MIN_COSINE = 0.05
# The balance corrects the sun's light: on faces turned from the sun (N·L at most 0) there is none
# to correct, and it eases from the fit to 1 as N·L falls from MIN_COSINE to 0.
BALANCE_RANGE = (0.5, 6.5)  # the fitted balance is held inside what the measurements spanned
DEGREE = 4
# exp(sum c v^i l^j a^k) over the terms (i, j, k), total degree at most DEGREE.
# The measured azimuths are 0, 90 and 180 degrees (a = 1, 0, -1), where a^3 = a: a's powers stop at 2.
AZIMUTH_POWERS = 2
TERMS = tuple(t for t in itertools.product(range(DEGREE + 1), repeat=3)
              if sum(t) <= DEGREE and t[2] <= AZIMUTH_POWERS)
# Fitted to devtools/eevee_balance.json (devtools/eevee_balance_data.py, Blender 5.2.3), under the
# EEVEE world's two hemispheres (addon/sky_eevee.py), for a boost that adds the sun's light alone.
COEFFICIENTS = (1.7328, 0.0126, 0.9607, -3.6286, -0.9463, -1.1328, -3.0546, 0.3508, 0.1306, 7.3925, 0.5289,
                -2.9587, -4.2059, -1.1353, -0.98, 13.9736, 1.6411, 1.0064, -7.661, -0.6189, -0.5374, -0.6202,
                0.8074, 0.0311, -8.5741, -0.9342, 5.2906, 5.0561, 0.3335, -0.0574, -2.286)


def _unit(vector):
    vector = np.asarray(vector, np.float64)
    length = np.linalg.norm(vector, axis=-1, keepdims=True)
    return vector / np.where(length > 0, length, 1.0)


def angles(view, light, normal):
    """(v, l, a) as the node group computes them; view and light point away from the surface."""
    view, light, normal = _unit(view), _unit(light), _unit(normal)
    v = np.sum(view * normal, axis=-1)
    l_ = np.sum(light * normal, axis=-1)
    across_v = view - v[..., None] * normal
    across_l = light - l_[..., None] * normal
    lengths = np.linalg.norm(across_v, axis=-1) * np.linalg.norm(across_l, axis=-1)
    # a = 1 with the sun in front of the camera: the view's across part points away from the sun's.
    a = -np.sum(across_v * across_l, axis=-1) / np.maximum(lengths, 1e-6)
    return np.maximum(v, MIN_COSINE), np.maximum(l_, MIN_COSINE), np.clip(a, -1.0, 1.0)


def design(v, l_, a):
    """The fit's terms for these angles: (..., len(TERMS))."""
    return np.stack([v ** i * l_ ** j * a ** k for i, j, k in TERMS], axis=-1)


def target(cycles, eevee, diffuse):
    """The balance that makes EEVEE's brightness `eevee` into Cycles' `cycles`, given what a unit
    of the Lambert diffuse adds (`diffuse`)."""
    ratio = np.asarray(cycles, np.float64) / np.asarray(eevee, np.float64)
    return np.where(ratio < 1.0, ratio, 1.0 + (ratio - 1.0) * np.asarray(eevee) / np.asarray(diffuse))


def balance(view, light, normal, coefficients=COEFFICIENTS):
    """The balance for the sand seen from `view` under a sun at `light`."""
    terms = design(*angles(view, light, normal))
    fitted = np.clip(np.exp(terms @ np.asarray(coefficients, np.float64)), *BALANCE_RANGE)
    facing = np.sum(_unit(light) * _unit(normal), axis=-1)
    return 1.0 + (fitted - 1.0) * np.clip(facing / MIN_COSINE, 0.0, 1.0)


def fit(v, l_, a, ratio):
    """Least-squares coefficients of log(balance) over the measured angles."""
    matrix = design(np.maximum(v, MIN_COSINE), np.maximum(l_, MIN_COSINE), a)
    coefficients, *_ = np.linalg.lstsq(matrix, np.log(ratio), rcond=None)
    return tuple(float(c) for c in coefficients)
