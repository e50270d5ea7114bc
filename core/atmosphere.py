"""Atmosphere physics in plain numpy: phase functions, Rayleigh coefficients, transmittance.

Seed 000, section 4.3: Rayleigh scattering goes as 1/lambda^4 and (1 + cos^2 theta); light
reaching the eye through a medium is attenuated by the transmittance exp(-beta d).
These are the numpy twins of what the Sandscape dust volume feeds Cycles (the RAYLEIGH and
HENYEY_GREENSTEIN phases of Volume Scatter, and the per-channel scattering colour).
"""

import numpy as np

from . import shaping

DEFAULT_WAVELENGTHS = (680.0, 550.0, 440.0)  # nm: red, green, blue
REFERENCE_WAVELENGTH = 550.0  # nm: the channel whose coefficient equals the set density
CONTRAST_THRESHOLD = 0.02  # Koschmieder: the eye just tells a dark object from the sky at 2 %


class AtmosphereError(ValueError):
    """Physically meaningless input (a wavelength of 0 nm, say)."""


def rayleigh_phase(cos_theta):
    """Rayleigh phase function 3 / (16 pi) (1 + cos^2), normalised over the sphere (1/sr)."""
    c = np.asarray(cos_theta, dtype=np.float64)
    return 3.0 / (16.0 * np.pi) * (1.0 + c * c)


def henyey_greenstein(cos_theta, g):
    """Henyey-Greenstein phase (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5), |g| < 1, per sr."""
    if not -1.0 < g < 1.0:
        raise AtmosphereError(f"anisotropy must lie in (-1, 1), got {g}")
    return shaping.henyey_greenstein(cos_theta, g)


def rayleigh_coefficients(density, wavelengths=DEFAULT_WAVELENGTHS, reference=REFERENCE_WAVELENGTH):
    """Scattering coefficients (1/m) per channel: density * (reference / lambda)^4.

    density is the coefficient at the reference wavelength; the ratio of any two channels
    is (lambda_i / lambda_j)^-4, the Rayleigh law.
    """
    wavelengths = np.asarray(wavelengths, dtype=np.float64)
    if not (np.isfinite(wavelengths).all() and (wavelengths > 0).all()):
        raise AtmosphereError(f"wavelengths must be positive, got {wavelengths.tolist()}")
    if not (np.isfinite(density) and density >= 0):
        raise AtmosphereError(f"density must be 0 or more, got {density}")
    return float(density) * (float(reference) / wavelengths) ** 4


def transmittance(optical_depth):
    """exp(-tau), finite and monotone for any tau >= 0 (it underflows to exactly 0)."""
    tau = np.asarray(optical_depth, dtype=np.float64)
    return np.exp(-np.maximum(tau, 0.0))


def slab_transmittance(coefficients, thickness):
    """Per-channel transmittance through a homogeneous slab: exp(-beta d)."""
    return transmittance(np.asarray(coefficients, dtype=np.float64) * float(thickness))


def haze_extinction(visibility):
    """Koschmieder: the extinction at which far terrain keeps CONTRAST_THRESHOLD of its contrast
    against the horizon sky at `visibility` (beta = ln(50) / V = 3.912 / V), per unit of 1 / V."""
    visibility = float(visibility)
    if not (np.isfinite(visibility) and visibility > 0):
        raise AtmosphereError(f"visibility must be above 0, got {visibility}")
    return float(np.log(1.0 / CONTRAST_THRESHOLD)) / visibility


def sun_direction(elevation, azimuth):
    """Unit vector towards the sun; azimuth is measured from +Y towards +X (compass style)."""
    return np.array([np.cos(elevation) * np.sin(azimuth), np.cos(elevation) * np.cos(azimuth),
                     np.sin(elevation)])


# EEVEE lights diffuse surfaces from the world's first two spherical-harmonic bands, and before
# that "derings" them: where the second band's largest axis exceeds this share of the first (in
# irradiance: (R1 . n) / R0 for a normal n), every channel's second band is scaled down to it.
# 5.0's is 2/3 (its source); 5.2's was measured (tests/test_eevee.py, worlds lit by two hemispheres).
EEVEE_DERING_LIMIT = {(5, 0): 2.0 / 3.0, (5, 2): 0.86}
EEVEE_DERING_MARGIN = 0.98  # our worlds keep this far inside the limit, so EEVEE leaves them as they are
# The two bands' brightest radiance is (1.25 below - 0.25 above) / pi: held at the clamp C, the
# ground may reach 0.2 sky + pi C / 1.25.
EEVEE_CLAMP_SKY_SHARE, EEVEE_CLAMP_BELOW_WEIGHT = 0.2, 1.25


def eevee_ground_ratio(limit):
    """How many times brighter (or darker) than the sky the ground may be without deringing."""
    return (1 + limit * EEVEE_DERING_MARGIN) / (1 - limit * EEVEE_DERING_MARGIN)


def eevee_world_irradiance(above, below, normal_z, limit, clamp=0.0):
    """Irradiance EEVEE gives a normal with up component normal_z under a world of two uniform
    hemispheres whose irradiance on level ground from above and from below is `above` and
    `below` (R, G, B): the first band (above + below)/2, the second (above - below)/2 along z,
    derung as EEVEE does (one factor for every channel), then all scaled down where the bands'
    brightest radiance, mean + 1.5 |tilt| over pi, passes the scene's Clamp Surface Indirect
    (0: off)."""
    above, below = np.asarray(above, np.float64), np.asarray(below, np.float64)
    mean, tilt = (above + below) / 2, (above - below) / 2
    share = np.abs(tilt) / np.maximum(mean, 1e-12)
    tilt = tilt * min(1.0, limit / max(float(share.max()), 1e-12))
    brightest = float(np.max(mean + 1.5 * np.abs(tilt))) / np.pi
    scale = min(1.0, clamp / brightest) if clamp > 0 and brightest > 0 else 1.0
    return np.maximum(mean + tilt * normal_z, 0.0) * scale


def eevee_world_hemispheres(sky, ground, limit, clamp=0.0):
    """The irradiance from above and from below (R, G, B) that EEVEE's lighting world holds, as
    two uniform hemispheres: from above the sky's on level ground, so level sand gets exactly the
    sky's light; from below the lit ground's (pi times its radiance), which lights a walker's legs
    and the undersides of things as the sand does in Cycles. The ground is held within the
    contrast EEVEE keeps without deringing (limit: EEVEE_DERING_LIMIT), so that the sky stays
    exact: a ground far brighter than the sky is dimmed, one far darker brightened; and below
    the scene's Clamp Surface Indirect (0: off), where the ground gives way, not the sky."""
    sky, ground = np.asarray(sky, np.float64), np.asarray(ground, np.float64)
    ratio = eevee_ground_ratio(limit)
    below = np.clip(ground, sky / ratio, sky * ratio)
    if clamp > 0:
        below = np.minimum(below, EEVEE_CLAMP_SKY_SHARE * sky + np.pi * clamp / EEVEE_CLAMP_BELOW_WEIGHT)
    return sky, below


def ground_radiance(direct, sky, albedo):
    """Radiance of level Lambertian ground, (R, G, B), under direct and sky irradiance on it."""
    irradiance = np.asarray(direct, np.float64) + np.asarray(sky, np.float64)
    return np.asarray(albedo, np.float64)[:3] * irradiance / np.pi

