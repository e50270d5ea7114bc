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


@pytest.mark.parametrize("version", sorted(air.EEVEE_DERING_LIMIT))
def test_the_two_hemispheres_light_level_sand_with_the_sky_and_legs_with_the_ground(version):
    """The EEVEE world's two hemispheres against a numpy integral of their radiance over the sphere,
    projected on two spherical-harmonic bands: level ground gets the sky's irradiance exactly, a
    downward face the ground's, a sideways one their mean, and EEVEE's deringing leaves them
    alone; for suns from 0 to 90 degrees over sand. On 5.0 a world holding the ground as it is
    would be derung under a high sun (level sand's sky light off by up to twice)."""
    from core import sun as sky_sun

    limit = air.EEVEE_DERING_LIMIT[version]
    up = np.linspace(-1.0, 1.0, 200001)

    def two_bands(radiance):  # (first band, second band along z) in irradiance, by trapezoids
        def integral(values):
            return 2 * np.pi * float(np.sum((values[1:] + values[:-1]) * np.diff(up)) / 2)
        return integral(radiance) / 4, integral(radiance * up) / 2

    derung_as_is = 0
    for degrees in (0.0, 3.0, 10.0, 30.0, 60.0, 90.0):
        direct, sky = sky_sun.level_irradiance(np.radians(degrees))
        ground = np.pi * air.ground_radiance(direct, sky, (0.62, 0.45, 0.27))
        above, below = air.eevee_world_hemispheres(sky, ground, limit)
        for channel in range(3):
            radiance = np.where(up > 0, above[channel], below[channel]) / np.pi
            mean, tilt = two_bands(radiance)
            assert abs(tilt) / mean < limit  # EEVEE's deringing leaves it alone
            assert mean + tilt == pytest.approx(sky[channel], rel=1e-4)
            assert mean - tilt == pytest.approx(below[channel], rel=1e-4)
        assert air.eevee_world_irradiance(above, below, 1.0, limit) == pytest.approx(sky, rel=1e-9)
        assert air.eevee_world_irradiance(above, below, 0.0, limit) == pytest.approx((sky + below) / 2)
        as_is = air.eevee_world_irradiance(sky, ground, 1.0, limit)
        derung_as_is += bool(np.abs(as_is / sky - 1).max() > 0.03)
        # The scene's Clamp Surface Indirect on (EEVEE's 10): the ground gives way, the sky stays.
        above, below = air.eevee_world_hemispheres(sky, ground, limit, clamp=10.0)
        clamped = air.eevee_world_irradiance(above, below, 1.0, limit, clamp=10.0)
        assert clamped == pytest.approx(sky, rel=1e-6)
    if version == (5, 0):  # 5.2 keeps a contrast of 12 to 1, about what lit sand gives
        assert derung_as_is >= 2


def test_eevees_deringing_scales_the_second_band_of_every_channel_alike():
    """The twin of EEVEE's world lighting on the cases measured in both versions (tests/test_eevee.py):
    a lit upper hemisphere gives level ground (1 + limit)/2 of its light; a contrast of 0.8 in one
    channel damps the others' second band with it; the clamp scales everything down."""
    assert air.eevee_world_irradiance([1.0] * 3, [0.0] * 3, 1.0, 2 / 3) == pytest.approx([5 / 6] * 3)
    lit = air.eevee_world_irradiance([1.0, 9.0, 9.0], [1.0, 1.0, 3.0], 1.0, 2 / 3)
    assert lit == pytest.approx([1.0, 5 + 4 * (2 / 3) / 0.8, 6 + 3 * (2 / 3) / 0.8])
    assert air.eevee_world_irradiance([9.0] * 3, [1.0] * 3, -1.0, 0.86) == pytest.approx([1.0] * 3)
    # Clamp Surface Indirect 10 on radiance 2.5 above, 23 below: brightest 12.75 + 15.375, so x 0.356.
    clamped = air.eevee_world_irradiance([2.5 * np.pi] * 3, [23 * np.pi] * 3, 1.0, 0.86, clamp=10.0)
    assert clamped / np.pi == pytest.approx([2.5 * 10 / 28.125] * 3)


def test_ground_radiance_is_albedo_times_irradiance_over_pi():
    radiance = air.ground_radiance([3.0, 2.0, 1.0], [1.0, 1.0, 1.0], (0.5, 0.25, 1.0, 1.0))
    assert radiance == pytest.approx(np.array([2.0, 0.75, 2.0]) / np.pi)
