"""The factors that bring our Physical Sand in EEVEE to Cycles' brightness, as functions of the
view, the sun and the surface: the twin of "Sandscape EEVEE Balance".

EEVEE has neither Cycles' rough (Oren-Nayar) diffuse nor its microfiber sheen: its diffuse is
Lambert and its sheen is lit like a diffuse. Under a low sun Cycles' sand is up to 4x brighter
seen with the sun behind (back-scatter at grazing angles), under a high sun EEVEE's is brighter,
and at grazing views Cycles' sand gets more of the sky's light. The EEVEE output (`surface`)
scales EEVEE's sand by min(G, 1), adds (G - 1) of the sand's own sun's part (EEVEE's sand less its
ambient) where G > 1 and the sun reaches, and adds (K - min(G, 1)) of the sand's ambient
(`sand_ambient`): G, the balance, corrects the sun's light and K, the ambient balance, the rest.
K is a factor per channel, its scalar fit times a tint (`ambient_tint`): EEVEE's sky-lit sand was
bluer than Cycles' at grazing views (Cycles' rough diffuse sees more of the warm horizon).
Both were measured on a flat plane of the sand under our sun and sky and under the sky alone
(devtools/eevee_balance_data.py; `solve` finds them per view) and fitted here as
exp(polynomial) in

    sqrt(v), sqrt(l) and p, where v = N·V, l = N·L (each at least MIN_COSINE) and p = the
    azimuth between V and L about N over pi (0: the sun in front of the camera; 1: behind it).

The square roots spread the grazing views and suns, where the balances change fastest; the
azimuth is taken as an angle, not its cosine, because toward a low sun Cycles' sand dims by a
quarter within 15 degrees of it, where the cosine hardly moves.

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
DEGREE = 6
# exp(sum c sqrt(v)^i sqrt(l)^j p^k) over the terms (i, j, k), total degree at most DEGREE, p's
# powers at most AZIMUTH_POWERS (the measured azimuths: 0, 20, 40, 60, 90 and 180 degrees).
AZIMUTH_POWERS = 3
TERMS = tuple(t for t in itertools.product(range(DEGREE + 1), repeat=3)
              if sum(t) <= DEGREE and t[2] <= AZIMUTH_POWERS)
# Fitted to devtools/eevee_balance.json (devtools/eevee_balance_data.py, Blender 5.2.3), under the
# EEVEE world's two hemispheres (addon/sky_eevee.py), the ambient from four unlit probes.
COEFFICIENTS = (-1.2257, 29.9966, -64.5965, 32.842, -22.6514, -21.5537, 155.9781, -82.6748, 89.2448,
                -149.4068, -43.3949, 47.7105, -79.2574, 207.9917, -92.7495, 3.7109, -42.2615,
                -33.7635, 43.2173, 85.2801, -31.8861, -29.3827, 27.0581, -152.3359, 248.2657,
                -110.3879, 28.1013, 208.3017, -426.6556, 159.1204, -288.8586, 101.2395, 219.151,
                -62.3166, 387.7691, -268.0895, -26.8193, -213.5021, 98.1781, 52.5581, -69.3103,
                174.0748, -236.8247, 92.6381, 115.3286, -191.3532, 253.6977, -62.7722, 112.6067,
                31.4387, -47.2478, -123.8099, 32.2486, 1.4071, 48.498, -66.9608, 62.0236, -18.8852,
                -205.4215, -10.3302, -45.0152, 14.8461, -3.2394, 54.393, 20.033, 35.9955, 2.4655,
                145.9648, 33.4319, -49.7244, -51.6815, -24.4838, -28.8813, 22.7879)
AMBIENT_COEFFICIENTS = (-0.2816, 0.3279, 0.3935, -0.7992, 6.0902, -8.1502, 6.771, -0.8519, -16.3965,
                        25.1549, -14.435, 3.5041, 14.2505, -34.818, 6.2266, -1.5318, 5.8046,
                        26.8459, 0.2095, -17.885, -8.9053, 8.454, -0.4411, 0.2892, 2.3571, 1.728,
                        2.2167, -11.1715, 0.2054, -3.7926, -2.4215, 13.4846, 7.9523, 0.2694, 9.6412,
                        -5.2838, -4.7975, -13.6884, -0.0145, 6.3871, 1.5545, 0.5566, -12.6882,
                        0.648, -6.3388, 21.6692, -2.0944, 1.9659, -6.4405, -26.0957, 2.0852,
                        10.0924, 8.3318, -5.1777, -4.0527, 2.9754, 13.7202, -1.2079, 10.0999,
                        -9.3432, -1.5792, 5.2091, 6.2373, -0.1334, 0.1206, -6.2311, -4.2332,
                        -9.2675, 1.4151, -4.077, 4.7247, 2.6949, 4.4357, -2.5546)
# The ambient balance's tint: exp(w AMBIENT_TINT_AXIS) per channel, w = sum c sqrt(v)^i sqrt(l)^j
# p^k over TERMS with AMBIENT_TINT_COEFFICIENTS, held in TINT_RANGE. The axis is the measured
# per-channel balances' main direction about the scalar one (their log ratios are near rank 1).
AMBIENT_TINT_AXIS = (1.0, 0.064, -0.88)
TINT_RANGE = (-0.1, 0.3)  # w as measured, -0.035..0.206, with a margin
AMBIENT_TINT_COEFFICIENTS = (0.0248, -0.1881, 1.4515, -1.1606, 0.7086, -3.0304, 1.1913, 1.0891,
                             -2.3626, 11.588, -6.9779, 0.4501, 1.6385, -16.1232, 5.0076, -0.2223,
                             1.0865, 11.5555, -0.9723, -1.7608, -3.6062, 0.6082, 1.2316, -1.2211,
                             -0.2346, 1.543, -1.3281, -1.4066, 1.275, -3.0667, 1.0977, 2.8383,
                             2.9481, 0.6302, -0.3964, -2.2877, -2.1645, -1.0572, 0.7569, 1.14,
                             -3.8275, 4.2748, -4.5326, 0.3043, 2.8485, 2.6051, 1.1787, 0.961,
                             -0.2599, -5.6427, 0.1848, 0.6673, 2.0656, -1.8111, 2.9088, -3.513,
                             3.5091, -0.5119, -3.3456, -2.644, -1.3252, 1.4289, 1.8886, 1.6806,
                             1.3603, 1.9895, -0.5619, 1.277, 1.0238, -2.3292, -2.7816, -0.9174,
                             0.5683, 0.9976)
# W(v) = sum_k SHEEN_AMBIENT[k] v^k per channel (`sheen_ambient`), fitted to the same measurements
# (EEVEE's sand under the sky alone over the ambient light at its normal, less the sand's colour).
SHEEN_AMBIENT = ((0.1019, 0.1361, 0.1601), (-0.2091, -0.2774, -0.3252), (0.1509, 0.2031, 0.2404),
                 (-0.0378, -0.0519, -0.0626))


def _unit(vector):
    vector = np.asarray(vector, np.float64)
    length = np.linalg.norm(vector, axis=-1, keepdims=True)
    return vector / np.where(length > 0, length, 1.0)


def angles(view, light, normal):
    """(v, l, p) as the node group computes them; view and light point away from the surface."""
    view, light, normal = _unit(view), _unit(light), _unit(normal)
    v = np.sum(view * normal, axis=-1)
    l_ = np.sum(light * normal, axis=-1)
    across_v = view - v[..., None] * normal
    across_l = light - l_[..., None] * normal
    lengths = np.linalg.norm(across_v, axis=-1) * np.linalg.norm(across_l, axis=-1)
    # a = 1 with the sun in front of the camera: the view's across part points away from the sun's.
    a = -np.sum(across_v * across_l, axis=-1) / np.maximum(lengths, 1e-6)
    return np.maximum(v, MIN_COSINE), np.maximum(l_, MIN_COSINE), np.arccos(np.clip(a, -1.0, 1.0)) / np.pi


def design(v, l_, p):
    """The fit's terms for these angles: (..., len(TERMS))."""
    root_v, root_l = np.sqrt(v), np.sqrt(l_)
    return np.stack([root_v ** i * root_l ** j * p ** k for i, j, k in TERMS], axis=-1)


def balance(view, light, normal, coefficients=COEFFICIENTS):
    """The balance for the sand seen from `view` under a sun at `light`."""
    log, sun_on_face = _fitted_log(view, light, normal, coefficients)
    return 1.0 + (np.clip(np.exp(log), *BALANCE_RANGE) - 1.0) * sun_on_face


def _fitted_log(view, light, normal, coefficients):
    """(sum c m over the fit's terms at these angles, the sun on the face: 0 where N·L is at most
    0, easing to 1 at MIN_COSINE); the fits ease to their value without a correction by it."""
    log = design(*angles(view, light, normal)) @ np.asarray(coefficients, np.float64)
    facing = np.sum(_unit(light) * _unit(normal), axis=-1)
    return log, np.clip(facing / MIN_COSINE, 0.0, 1.0)


def ambient_balance(view, light, normal, coefficients=AMBIENT_COEFFICIENTS):
    """The factor on the light less the sun's (the sky's, the haze's, the ground's) for the sand
    seen from `view` under a sun at `light`: Cycles' sky-lit sand over EEVEE's. Measured on faces
    the sun reaches; on faces turned from it (N·L at most 0), which see no bright sky round the
    sun, 1, easing in as the balance does (a helper's dune slopes turned from a 10° sun: EEVEE
    +16 % of Cycles without it, +22 % with it)."""
    log, sun_on_face = _fitted_log(view, light, normal, coefficients)
    return 1.0 + (np.clip(np.exp(log), *AMBIENT_RANGE) - 1.0) * sun_on_face


def ambient_tint(view, light, normal, coefficients=AMBIENT_TINT_COEFFICIENTS):
    """The ambient balance's factor per channel (..., 3) about its scalar fit: warmer than 1 in
    red where Cycles' sky-lit sand is warmer than EEVEE's; 1 on faces turned from the sun."""
    log, sun_on_face = _fitted_log(view, light, normal, coefficients)
    warmth = np.clip(log, *TINT_RANGE) * sun_on_face
    return np.exp(warmth[..., None] * np.asarray(AMBIENT_TINT_AXIS, np.float64))


def fit_tint(v, l_, p, ratio):
    """Least-squares AMBIENT_TINT_COEFFICIENTS: w over the measured angles from the per-channel
    ratios (..., 3) of the balance needed to the scalar one, w = log(ratio) projected on the axis."""
    axis = np.asarray(AMBIENT_TINT_AXIS, np.float64)
    warmth = np.log(np.asarray(ratio, np.float64)) @ axis / (axis @ axis)
    matrix = design(np.maximum(v, MIN_COSINE), np.maximum(l_, MIN_COSINE), p)
    coefficients, *_ = np.linalg.lstsq(matrix, warmth, rcond=None)
    return tuple(float(c) for c in coefficients)


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


def fit(v, l_, p, ratio, weights=None):
    """Least-squares coefficients of log(balance) over the measured angles, each row weighted by
    `weights` (None: 1)."""
    matrix = design(np.maximum(v, MIN_COSINE), np.maximum(l_, MIN_COSINE), p)
    weights = np.ones(len(matrix)) if weights is None else np.asarray(weights, np.float64)
    coefficients, *_ = np.linalg.lstsq(matrix * weights[:, None], np.log(ratio) * weights, rcond=None)
    return tuple(float(c) for c in coefficients)


def fit_sheen_ambient(v, excess):
    """Least-squares SHEEN_AMBIENT for W(v) = `excess` (..., 3) at N·V = v."""
    v = np.maximum(np.asarray(v, np.float64), MIN_COSINE)
    matrix = np.stack([v ** k for k in range(len(SHEEN_AMBIENT))], axis=-1)
    coefficients, *_ = np.linalg.lstsq(matrix, np.asarray(excess, np.float64), rcond=None)
    return tuple(tuple(round(float(c), 4) for c in row) for row in coefficients)
