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


# EEVEE's damping of its second band, by Blender version: from a lit upper hemisphere, which
# renders at (1 + b) / 2 of Cycles' light (tests/test_eevee.py, the upper hemisphere).
EEVEE_BAND_ONE = {(5, 0): 0.66, (5, 2): 0.86}


def eevee_sky_weight(up, band_one):
    """The factor on the sky's radiance in EEVEE's lighting world, by the direction's up component.

    EEVEE lights diffuse surfaces from the world's first two spherical-harmonic bands, where a
    direction d reaches a normal n with weight 1/4 + b (d.n)/2 (per unit of radiance, over pi; b
    its damping of the second band) instead of max(0, d.n). A low sun's bright, warm sky near the
    horizon then lights flat sand three times over. Weighted by max(0, d_z) / (1/4 + b d_z/2), the
    sky lights an upward normal as the true integral does, for any sky; below the horizon, nothing.
    """
    up = np.maximum(np.asarray(up, np.float64), 0.0)
    return up / (0.25 + 0.5 * band_one * up)
