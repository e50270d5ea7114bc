"""The cloud layer's light on level ground: what EEVEE's lighting world adds for it.

Cycles lights the sand with the clouds' scattered sunlight: under a low sun, their faces lit gold
across the sky. EEVEE's volumes light no surface, so its lighting world (two hemispheres of the
clear sky's light, addon/sky_eevee.py) adds the clouds' as a change of the light from above:

    change = (D + G x the sand's colour) x the lamp's irradiance (on a surface facing it)
             - B x the clear sky's on level ground

D (the share of the sun's light the clouds send down), G (the sunlit sand's light their bases
send back, in the same units) and B (the share of the sky's light they take away: what they hide
less what they pass on) are measured in Cycles under the demo's layer, the mean over 30 km of
sand, by sun elevation and coverage (core/cloud_light_table.py, devtools/cloud_light_table.py),
and interpolated here: linearly in the sine of the sun's elevation and in coverage, none at
coverage 0, D and G falling to none at the horizon, all held beyond the table's highest sun;
scaled by the optical depth's ratio to the table's. A uniform world holds the mean: one place
under broken cloud gets more or less than it (bench/RESULTS.md, "Cloud light").
"""

import numpy as np

from . import cloud_light_table as table
from .sand import SAND_COLOR

_ROWS = np.array([[row[0]] + [v for shares in row[1:] for v in shares] for row in table.ROWS], np.float64)
_DEGREES = _ROWS[:, 0]
_D, _G, _B = _ROWS[:, 1::3], _ROWS[:, 2::3], _ROWS[:, 3::3]  # (elevations, coverages)
_COVERAGES = np.array((0.0,) + tuple(table.COVERAGES))


def _in_coverage(values, coverage):
    """Each elevation's value at this coverage: linear between the table's, none at coverage 0."""
    c = float(np.clip(coverage, 0.0, 1.0))
    padded = np.concatenate([np.zeros((len(values), 1)), values], axis=1)
    return np.array([np.interp(c, _COVERAGES, row) for row in padded])


def depth_scale(optical_depth, exponent):
    """The measured shares' scale at another optical depth (density x thickness)."""
    ratio = max(float(optical_depth), 0.0) / table.OPTICAL_DEPTH
    return ratio ** exponent if ratio > 0 else 0.0


def curves(coverage, optical_depth):
    """(degrees, D, G, B): the shares at each measured sun elevation for this layer, with the
    horizon's row first (D and G none there, B as at the lowest measured sun)."""
    d = np.maximum(_in_coverage(_D, coverage) * depth_scale(optical_depth, table.D_EXPONENT), 0.0)
    g = np.maximum(_in_coverage(_G, coverage) * depth_scale(optical_depth, table.G_EXPONENT), 0.0)
    b = np.clip(_in_coverage(_B, coverage) * depth_scale(optical_depth, table.B_EXPONENT), 0.0, 1.0)
    return (np.concatenate([[0.0], _DEGREES]), np.concatenate([[0.0], d]), np.concatenate([[0.0], g]),
            np.concatenate([[b[0]], b]))


def shares(elevation, coverage, optical_depth):
    """(D, G, B) at a sun elevation in radians, linear in its sine between the measured
    elevations (as the world's curve); the sun below the horizon: (0, 0, B at the horizon)."""
    degrees, *values = curves(coverage, optical_depth)
    sines = np.sin(np.radians(degrees))
    at = float(np.clip(np.sin(float(elevation)), 0.0, sines[-1]))
    return tuple(float(np.interp(at, sines, v)) for v in values)


def level_change(elevation, coverage, optical_depth, sun, sky, ground=SAND_COLOR):
    """The change of the light on level ground (R, G, B) the layer makes: `sun` the lamp's
    irradiance on a surface facing it, `sky` the clear sky's on level ground, each (R, G, B),
    `ground` the sand's colour."""
    d, g, b = shares(elevation, coverage, optical_depth)
    tint = d + g * np.asarray(ground, np.float64)[:3]
    return tint * np.asarray(sun, np.float64) - b * np.asarray(sky, np.float64)


def eddington_slab(optical_depth, asymmetry, mu0, ground=0.0):
    """(sun, sky): the diffuse light a uniform, non-absorbing slab passes on to ground of this
    albedo, as a share of the sun's irradiance on a surface facing it (the beam at cosine mu0 to
    the vertical) and of an even sky's irradiance; the Eddington two-stream solution with the
    similarity-scaled depth tau (1 - g) (Joseph, Wiscombe & Weinman 1976; Meador & Weaver 1980,
    conservative case), the ground's light sent back by the slab's base (reflectance 1 - T for an
    even sky) summed over every bounce."""
    scaled = max(float(optical_depth), 0.0) * (1.0 - float(asymmetry))
    mu0 = float(mu0)
    total = (0.5 + 0.75 * mu0 + (0.5 - 0.75 * mu0) * np.exp(-scaled / mu0)) / (1.0 + 0.75 * scaled)
    even = 1.0 / (1.0 + 0.75 * scaled)
    bounces = 1.0 / (1.0 - float(ground) * (1.0 - even))
    return mu0 * (total - np.exp(-scaled / mu0)) * bounces, even * bounces
