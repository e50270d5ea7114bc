"""The factors that bring our Physical Sand in EEVEE to Cycles' brightness, as functions of the
view, the sun and the surface: the twin of "Sandscape EEVEE Balance".

EEVEE has neither Cycles' rough (Oren-Nayar) diffuse nor its microfiber sheen: its diffuse is
Lambert and its sheen is lit like a diffuse. Under a low sun Cycles' sand is up to 4x brighter
seen with the sun behind (back-scatter at grazing angles), under a high sun EEVEE's is brighter,
and at grazing views Cycles' sand gets more of the sky's light. The EEVEE output (`surface`)
scales EEVEE's sand by min(G, 1), adds (G - 1) of the sand's own sun's part (EEVEE's sand less its
ambient) where G > 1 and the sun reaches, and adds (K - min(G, 1)) of the sand's ambient
(`sand_ambient`): G, the balance, corrects the sun's light and K, the ambient balance, the rest.
Both were measured on a flat plane of the sand under our sun and sky and under the sky alone
(devtools/eevee_balance_data.py; `solve` finds them per view) and fitted here as
exp(polynomial) in

    sqrt(v), sqrt(l) and a, where v = N·V, l = N·L (each at least MIN_COSINE) and a = cos of the
    azimuth between V and L about N (a = 1: the sun in front of the camera; -1: behind it).

The square roots spread the grazing views and suns, where the balances change fastest.

The fits are a calibration, not physics; their reference is Cycles itself (bench/eevee.py
measures an EEVEE frame against a Cycles one).
"""

import itertools

import numpy as np

MIN_COSINE = 0.05
# The balance corrects the sun's light: on faces turned from the sun (N·L at most 0) there is none
# to correct, and it eases from the fit to 1 as N·L falls from MIN_COSINE to 0 (the ambient
# balance too: it was measured on faces the sun reaches).
BALANCE_RANGE = (0.3, 6.5)  # the fitted balance is held inside what the measurements spanned
AMBIENT_RANGE = (0.7, 2.0)
DEGREE = 5
# exp(sum c sqrt(v)^i sqrt(l)^j a^k) over the terms (i, j, k), total degree at most DEGREE.
# The measured azimuths are 0, 90 and 180 degrees (a = 1, 0, -1), where a^3 = a: a's powers stop at 2.
AZIMUTH_POWERS = 2
TERMS = tuple(t for t in itertools.product(range(DEGREE + 1), repeat=3)
              if sum(t) <= DEGREE and t[2] <= AZIMUTH_POWERS)
# Fitted to devtools/eevee_balance.json (devtools/eevee_balance_data.py, Blender 5.2.3), under the
# EEVEE world's two hemispheres (addon/sky_eevee.py), the ambient from four unlit probes.
COEFFICIENTS = (-0.5198, -3.3614, -1.8483, -4.5304, -3.0036, 6.915, 37.5195, 33.7678, -7.6922,
                -87.176, -46.1144, 2.4124, 78.4788, 18.8647, -23.9537, 19.2964, 22.9028, 6.3432,
                -32.7661, -54.2328, -8.6168, 12.8758, 29.0157, 3.6657, 0.048, -0.2096, -3.2028,
                -50.4231, -24.9169, -6.8154, 68.6246, 55.5222, 3.7493, -1.8362, -22.6291, -5.4271,
                47.3306, 2.6035, 1.9806, -63.1907, -12.5762, 6.4873, -15.1906, 4.4039, 16.4772,
                0.8887)
AMBIENT_COEFFICIENTS = (-0.9215, -0.2535, 0.0273, 9.877, 0.493, 0.6654, -32.8066, 0.0498, -1.1244,
                        53.6902, -1.0846, 0.3868, -44.3555, 0.7268, 14.6966, 1.9923, 1.3864, 0.1728,
                        -3.1211, -3.2196, -0.3298, 5.8968, 2.4381, 0.3697, -4.655, -0.2487, 0.5311,
                        -5.2522, -1.8578, -0.4466, 0.2261, 2.9385, 0.1268, 1.4326, -1.7067, 1.059,
                        5.2703, 0.5953, 0.1582, -0.8521, -0.3852, -1.6853, -2.4049, 0.1346, 0.7727,
                        0.5273)
# W(v) = sum_k SHEEN_AMBIENT[k] v^k per channel (`sheen_ambient`), fitted to the same measurements
# (EEVEE's sand under the sky alone over the ambient light at its normal, less the sand's colour).
SHEEN_AMBIENT = ((0.1021, 0.1363, 0.1603), (-0.2129, -0.2809, -0.3279), (0.1589, 0.2104, 0.2461),
                 (-0.0421, -0.0559, -0.0657))

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
    root_v, root_l = np.sqrt(v), np.sqrt(l_)
    return np.stack([root_v ** i * root_l ** j * a ** k for i, j, k in TERMS], axis=-1)


def balance(view, light, normal, coefficients=COEFFICIENTS):
    """The balance for the sand seen from `view` under a sun at `light`."""
    terms = design(*angles(view, light, normal))
    fitted = np.clip(np.exp(terms @ np.asarray(coefficients, np.float64)), *BALANCE_RANGE)
    facing = np.sum(_unit(light) * _unit(normal), axis=-1)
    return 1.0 + (fitted - 1.0) * np.clip(facing / MIN_COSINE, 0.0, 1.0)


def ambient_balance(view, light, normal, coefficients=AMBIENT_COEFFICIENTS):
    """The factor on the light less the sun's (the sky's, the haze's, the ground's) for the sand
    seen from `view` under a sun at `light`: Cycles' sky-lit sand over EEVEE's. Measured on faces
    the sun reaches; on faces turned from it (N·L at most 0), which see no bright sky round the
    sun, 1, easing in as the balance does (a helper's dune slopes turned from a 10° sun: EEVEE
    +16 % of Cycles without it, +22 % with it)."""
    terms = design(*angles(view, light, normal))
    fitted = np.clip(np.exp(terms @ np.asarray(coefficients, np.float64)), *AMBIENT_RANGE)
    facing = np.sum(_unit(light) * _unit(normal), axis=-1)
    return 1.0 + (fitted - 1.0) * np.clip(facing / MIN_COSINE, 0.0, 1.0)


def sheen_ambient(v, coefficients=SHEEN_AMBIENT):
    """W(v): what EEVEE's own sand adds to the ambient light at the normal times its colour, per
    channel and per unit of that light, seen at N·V = v (its sheen and specular, at grazing views)."""
    v = np.maximum(np.asarray(v, np.float64), MIN_COSINE)[..., None]
    return sum(np.asarray(c, np.float64) * v ** k for k, c in enumerate(coefficients))


def sand_ambient(ambient, colour, v):
    """EEVEE's own sand under the light less the sun's: the ambient light at the normal (a white
    Lambert surface's, per channel) times the sand's colour plus W(v)."""
    return np.asarray(ambient, np.float64) * (np.asarray(colour, np.float64)[..., :3] + sheen_ambient(v))


def surface(sand, ambient, balance_, ambient_balance_, reach=1.0):
    """What the EEVEE output gives, from EEVEE's own sand (`sand`) and its estimate of that sand
    under the light less the sun's (`ambient`, `sand_ambient`): the sand scaled by the balance
    where it is below 1, its sun's part (the sand less the ambient) times (balance - 1) added
    where the sun reaches (`reach`, 0..1) and the balance is above 1, and the ambient times
    (ambient balance - the scale) added."""
    sand, ambient = np.asarray(sand, np.float64), np.asarray(ambient, np.float64)
    scale = np.minimum(balance_, 1.0)
    return (scale * sand + np.maximum(balance_ - 1.0, 0.0) * reach * (sand - ambient)
            + (ambient_balance_ - scale) * ambient)


def solve(full, sky):
    """(balance, ambient balance) that make `surface` give Cycles' brightness both under the sun
    and sky (`full`, the sun reaching) and under the sky alone (`sky`, no sun to reach): each a
    dict of brightnesses "cycles", "eevee" (EEVEE's own sand) and "ambient" (`sand_ambient`)."""
    def pair(boosting):
        # s (S - A) + K A = C where the balance scales; S + p (S - A) reach + (K - 1) A = C where it adds.
        matrix, right = [], []
        for lit, reach in ((full, 1.0), (sky, 0.0)):
            sun_part = lit["eevee"] - lit["ambient"]
            matrix.append((sun_part * (reach if boosting else 1.0), lit["ambient"]))
            right.append(lit["cycles"] - (sun_part if boosting else 0.0))
        return np.linalg.solve(np.array(matrix, np.float64), right)

    scale, ambient = pair(False)
    if scale <= 1.0:
        return float(scale), float(ambient)
    boost, ambient = pair(True)
    return float(1.0 + boost), float(ambient)


def fit(v, l_, a, ratio, weights=None):
    """Least-squares coefficients of log(balance) over the measured angles, each row weighted by
    `weights` (None: 1)."""
    matrix = design(np.maximum(v, MIN_COSINE), np.maximum(l_, MIN_COSINE), a)
    weights = np.ones(len(matrix)) if weights is None else np.asarray(weights, np.float64)
    coefficients, *_ = np.linalg.lstsq(matrix * weights[:, None], np.log(ratio) * weights, rcond=None)
    return tuple(float(c) for c in coefficients)


def fit_sheen_ambient(v, excess):
    """Least-squares SHEEN_AMBIENT for W(v) = `excess` (..., 3) at N·V = v."""
    v = np.maximum(np.asarray(v, np.float64), MIN_COSINE)
    matrix = np.stack([v ** k for k in range(len(SHEEN_AMBIENT))], axis=-1)
    coefficients, *_ = np.linalg.lstsq(matrix, np.asarray(excess, np.float64), rcond=None)
    return tuple(tuple(round(float(c), 4) for c in row) for row in coefficients)
