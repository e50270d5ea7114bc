"""Atmosphere twins: phase functions normalised, Rayleigh law, transmittance well behaved."""

import numpy as np
import pytest

from core import atmosphere as air


def sphere_integral(phase):
    """2 pi * integral over cos(theta) in [-1, 1], by 400-point Gauss-Legendre."""
    mu, weights = np.polynomial.legendre.leggauss(400)
    return 2 * np.pi * np.sum(weights * phase(mu))


def test_rayleigh_phase_integrates_to_one():
    assert abs(sphere_integral(air.rayleigh_phase) - 1.0) < 1e-6
    # Independent check: a plain Riemann sum over a (theta, phi) grid of the sphere.
    theta = (np.arange(20000) + 0.5) / 20000 * np.pi
    total = 2 * np.pi * np.sum(air.rayleigh_phase(np.cos(theta)) * np.sin(theta)) * np.pi / 20000
    assert abs(total - 1.0) < 1e-6
    assert air.rayleigh_phase(1.0) == pytest.approx(2 * air.rayleigh_phase(0.0))  # 1 + cos^2


@pytest.mark.parametrize("g", [-0.6, 0.0, 0.3, 0.8])
def test_henyey_greenstein_integrates_to_one(g):
    assert abs(sphere_integral(lambda mu: air.henyey_greenstein(mu, g)) - 1.0) < 1e-6


def test_henyey_greenstein_refuses_g_of_one():
    with pytest.raises(air.AtmosphereError):
        air.henyey_greenstein(0.5, 1.0)


def test_coefficients_follow_the_inverse_fourth_power():
    wavelengths = np.array([680.0, 550.0, 440.0])
    beta = air.rayleigh_coefficients(0.02, wavelengths)
    assert beta[1] == pytest.approx(0.02, rel=1e-12)  # the reference channel is the set density
    for i in range(3):
        for j in range(3):
            assert abs(beta[i] / beta[j] - (wavelengths[i] / wavelengths[j]) ** -4) < 1e-6
    assert beta[2] > beta[1] > beta[0]  # blue scatters most


@pytest.mark.parametrize("wavelengths", [(680, 0, 440), (680, -550, 440), (680, np.nan, 440)])
def test_bad_wavelengths_are_refused(wavelengths):
    with pytest.raises(air.AtmosphereError, match="wavelengths"):
        air.rayleigh_coefficients(0.02, wavelengths)


def test_transmittance_is_finite_and_monotone_up_to_ten_thousand():
    tau = np.linspace(0.0, 1e4, 200001)
    t = air.transmittance(tau)
    assert np.isfinite(t).all()
    assert t[0] == pytest.approx(1.0, abs=1e-12) and t[-1] == pytest.approx(0.0, abs=1e-12)
    assert (np.diff(t) <= 0).all()
    assert air.slab_transmittance([0.1, 0.2], 3.0) == pytest.approx(np.exp([-0.3, -0.6]))


def test_sun_direction_is_a_unit_vector_up_at_ninety_degrees():
    assert np.linalg.norm(air.sun_direction(0.3, 2.0)) == pytest.approx(1.0)
    assert air.sun_direction(np.pi / 2, 1.0) == pytest.approx([0.0, 0.0, 1.0])
    assert air.sun_direction(0.0, 0.0) == pytest.approx([0.0, 1.0, 0.0])


def test_the_weighted_sky_lights_upward_ground_exactly_through_two_bands():
    """The weight of EEVEE's lighting sky, against a numpy integral over the sphere: for skies
    bright near the horizon, overhead or below it, the first two spherical-harmonic bands (the
    second damped as EEVEE does) give an upward normal the exact cosine-weighted irradiance;
    without the weight a low bright sky lights the ground up to three times over."""
    rng = np.random.default_rng(7)
    up = np.linspace(-1.0, 1.0, 4001)  # the sphere in equal-area bands of d_z (azimuth integrated)
    band = air.EEVEE_BAND_ONE[(5, 2)]
    weight = air.eevee_sky_weight(up, band)

    def integral(values):  # over d_z, trapezoids
        return float(np.sum((values[1:] + values[:-1]) * np.diff(up)) / 2)

    for _ in range(20):
        glow, width = rng.uniform(-0.2, 1.0), rng.uniform(0.02, 0.5)  # a bright band of sky
        radiance = 0.2 + rng.uniform(1.0, 50.0) * np.exp(-((up - glow) / width) ** 2)
        exact = integral(radiance * np.maximum(up, 0.0))
        through_bands = integral(radiance * weight * (0.25 + 0.5 * band * up))
        assert through_bands == pytest.approx(exact, rel=1e-9)
    low = np.exp(-((up - 0.1) / 0.05) ** 2)  # a low sun's glow
    plain = integral(low * (0.25 + 0.5 * band * up)) / integral(low * np.maximum(up, 0.0))
    assert plain > 2.5
