"""Shadow rays through free-standing films: attenuated by T = 1 - R, not blocked;
light through films counted once (MIS on and off agree)."""

import numpy as np

from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec
from helpers.thin_film import thin_film_reflectance
from engine.tracer.spectra.trapezoid import trapezoid

from .tracer_scenes import look_at, make_scene, quad, settings

FILM = Material("soap", kind="thin_film", film_thickness_nm=300.0, film_ior=1.33)


def _scene(light):
    cam = Camera("cam", look_at((0, 0, 1.0), (0, 0, 0), up=(0, 1, 0)), (8, 8), film_width_mm=4.0,
                 film_height_mm=4.0)
    floor = quad((0, 0, 0), (3, 0, 0), (0, 3, 0))
    film = quad((0, 0, 1.5), (3, 0, 0), (0, 3, 0))
    return make_scene([(*floor, 0), (*film, 1)], [Material("floor", base_color=(0.5, 0.5, 0.5)), FILM], cam,
                      [light])


def test_point_light_behind_a_soap_film_is_attenuated_not_blocked():
    light = Light("lamp", "point", np.array([0.0, 0.0, 2.0]), power_w=100.0)
    r = Renderer(_scene(light), settings(samples=64, samples_per_pass=64))
    assert "see-through film shadows" in r.strategy
    r.render_pass()
    # near-normal incidence everywhere (narrow view): T(lambda) of the film at normal incidence
    lam = np.linspace(360.0, 830.0, 4701)
    t = 1.0 - thin_film_reflectance(1.0, lam, 300.0, 1.0, 1.33, 1.0)
    white = emission_spectrum(SpectrumSpec()).evaluate(lam)
    xyz = trapezoid((white * t)[:, None] * cie.cie_xyz_cmf(lam), lam, axis=0) / cie.CMF_Y_INTEGRAL
    expected = 100 / (4 * np.pi) * 0.5 / (np.pi * 4.0) * cie.xyz_to_linear_rec709(xyz)
    got = r.image_rgb().astype(np.float64).mean((0, 1))
    assert np.allclose(got, expected, rtol=0.03), (got, expected)
    assert r.stats["nan_samples"] == 0


def test_light_through_films_is_counted_once():
    light = Light("bulb", "point", np.array([0.0, 0.0, 2.2]), power_w=100.0, radius_m=0.3)
    out = []
    for mis in (True, False):
        r = Renderer(_scene(light), settings(samples=64, samples_per_pass=64, use_mis=mis, max_bounces=2))
        r.render_pass()
        out.append((r.image_rgb().astype(np.float64).mean((0, 1)), r.variance_rgb().astype(np.float64).mean((0, 1))))
    (a, va), (b, vb) = out
    assert np.all(np.abs(a - b) < 4 * np.sqrt((va + vb) / 64) + 1e-3 * a.max()), (a, b)
