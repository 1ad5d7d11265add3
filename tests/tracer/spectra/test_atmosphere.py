"""The Nishita sky per wavelength: closed-form columns and transmittance, the Rayleigh optical depth of
the literature, the colours a clear sky must have, Blender's ground fade, and the Sun disc's irradiance
(limb darkening included) through light sampling."""

import math

import numpy as np
import pytest

from engine.tracer.scene import Camera, Material, Sky, World
from engine.tracer.spectra import atmosphere as A
from engine.tracer.spectra import cie
from engine.tracer.spectra.trapezoid import trapezoid

from ..lights.light_checks import SceneLights
from ..tracer_scenes import make_scene


def test_zenith_columns_are_the_closed_form():
    """Straight up from sea level: ∫ exp(-h/H) dh = H (1 - exp(-60 km/H)); the ozone tent 15 km."""
    top = A.ATMOSPHERE_RADIUS_M - A.EARTH_RADIUS_M
    for steps, tolerance in ((256, 2e-4), (A.SUN_STEPS, 2e-3)):
        air, aerosol, ozone = A.column_densities(0.0, 0.0, A.EARTH_RADIUS_M, 0.0, 0.0, 1.0, steps)
        assert air == pytest.approx(A.RAYLEIGH_SCALE_HEIGHT_M * (1 - math.exp(-top / A.RAYLEIGH_SCALE_HEIGHT_M)),
                                    rel=tolerance)
        assert aerosol == pytest.approx(A.MIE_SCALE_HEIGHT_M * (1 - math.exp(-top / A.MIE_SCALE_HEIGHT_M)),
                                        rel=tolerance)
        assert ozone == pytest.approx(A.OZONE_HALF_WIDTH_M, rel=tolerance)


def test_rayleigh_optical_depth_and_zenith_transmittance():
    """Rayleigh optical depth of the whole atmosphere at 550 nm within 2 % of the literature's 0.0973
    (Bucholtz 1995); the Sun at the zenith is transmitted as exp(-Σ β column)."""
    assert A.rayleigh_scattering_per_m(550.0) * A.RAYLEIGH_SCALE_HEIGHT_M == pytest.approx(0.0973, rel=0.02)
    transmittance = A.sun_transmittance(math.pi / 2, 0.0, np.ones(3))
    coeff = A.coefficients(A.SKY_WAVELENGTHS_NM)
    top = A.ATMOSPHERE_RADIUS_M - A.EARTH_RADIUS_M
    columns = np.array([A.RAYLEIGH_SCALE_HEIGHT_M * (1 - math.exp(-top / A.RAYLEIGH_SCALE_HEIGHT_M)),
                        A.MIE_SCALE_HEIGHT_M * (1 - math.exp(-top / A.MIE_SCALE_HEIGHT_M)), A.OZONE_HALF_WIDTH_M])
    expected = np.exp(-(coeff[:, 0] * columns[0] + coeff[:, 2] * columns[1] + coeff[:, 3] * columns[2]))
    assert np.allclose(transmittance, expected, rtol=1e-3)
    assert transmittance[0] < transmittance[-1]  # blue is scattered out more than red


def _rgb(spectrum):
    lam = A.SKY_WAVELENGTHS_NM
    xyz = trapezoid(np.asarray(spectrum, float)[..., None] * cie.cie_xyz_cmf(lam), lam, axis=-2)
    return cie.xyz_to_linear_rec709(xyz)


def test_a_clear_sky_is_blue_overhead_and_red_at_sunset():
    noon = A.sky_tables(Sky(sun_elevation_rad=math.radians(60)), elevations=17, azimuths=17)
    zenith = _rgb(noon.radiance[-1, 0])
    assert zenith[2] > zenith[1] > zenith[0] > 0
    assert _rgb(noon.radiance[0, -1])[2] / _rgb(noon.radiance[0, -1])[0] < zenith[2] / zenith[0]  # paler horizon
    sunset = A.sky_tables(Sky(sun_elevation_rad=math.radians(2)), elevations=17, azimuths=17)
    toward, away = _rgb(sunset.radiance[0, 0]), _rgb(sunset.radiance[0, -1])
    assert toward[0] > toward[2] and toward[0] > 10 * away[0]
    assert (_rgb(sunset.sun_radiance)[0] / _rgb(sunset.sun_radiance)[2]
            > 5 * _rgb(noon.sun_radiance)[0] / _rgb(noon.sun_radiance)[2])  # a red setting Sun
    # Blender's ground: the horizon faded to black at sin(elevation) = -0.4.
    assert A.ground_fade(0.0) == 1.0 and A.ground_fade(-0.4) == 0.0 and A.ground_fade(-0.2) == pytest.approx(0.125)


def test_the_sky_sun_delivers_its_transmitted_irradiance():
    """Light-sampled irradiance of the sky's Sun on a surface facing it = E_sun(λ) T(λ) × 0.8 (the
    mean of Blender's limb darkening 1 - 0.6 (1 - μ) over the disc) × Sun Intensity × Strength."""
    sky = Sky(sun_elevation_rad=math.radians(40), sun_rotation_rad=math.radians(30), sun_size_rad=math.radians(2),
              sun_intensity=1.5)
    scene = make_scene([], [Material("m")], Camera("c", np.eye(4), (1, 1)), world=World(kind="sky", sky=sky,
                                                                                        strength=0.5))
    lights = SceneLights(scene)
    sun = lights.table.names.index("World sun")
    toward = lights.arrays.rows[sun, 6:9]
    e, rot = sky.sun_elevation_rad, sky.sun_rotation_rad
    assert np.allclose(toward, [math.cos(e) * math.sin(rot), math.cos(e) * math.cos(rot), math.sin(e)])
    n = 200_000
    u = np.random.default_rng(2).random((n, 3))
    u[:, 2] = lights.arrays.select_cdf[sun] - 0.5 * lights.arrays.select_prob[sun]  # always the Sun
    for wavelength in (450.0, 550.0, 650.0):
        s = lights.sample(np.zeros((n, 3)), u, wavelength)
        irradiance = np.mean(s.li * (s.wi @ toward) / (s.pdf / lights.arrays.select_prob[sun]))
        transmittance = np.interp(wavelength, A.SKY_WAVELENGTHS_NM, A.sun_transmittance(e, 0.0, np.ones(3)))
        expected = A.solar_irradiance(wavelength) * transmittance * 0.8 * 1.5 * 0.5 * cie.CMF_Y_INTEGRAL
        assert irradiance == pytest.approx(expected, rel=0.01)
