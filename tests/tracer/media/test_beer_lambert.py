"""Beer-Lambert: a slab of Volume Absorption (a null surface around a medium) in front of an emitter
transmits, per wavelength, exactly exp(-σ_a(λ) d) of its light, σ_a(λ) = density × (1 - R(λ)) with R the
colour's upsampled reflectance. Measured band by band with the spectral film against the same render
without the slab (same seed: the same wavelengths), so only the slab differs."""

import numpy as np
import pytest

from engine.tracer.media.spec import MediumSpec
from engine.tracer.media.table import coefficient_spectra
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec
from engine.tracer.spectra.wavelengths import VISIBLE_NM_GRID

from ..tracer_scenes import look_at, make_scene, quad, settings

THICKNESS_M = 0.5
COLOUR = (0.9, 0.5, 0.2)
DENSITY = 2.0


def _box(center, half):
    """A closed box (outward normals) of half-extents ``half``."""
    c, h = np.asarray(center, float), np.asarray(half, float)
    corners = np.array([[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]) * h + c
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    tris = np.array([[f[0], f[1], f[2]] for f in faces] + [[f[0], f[2], f[3]] for f in faces])
    return corners, tris


def _scene(with_slab, point_light=False):
    # A narrow camera straight down: every ray crosses the slab within 0.001 % of its thickness.
    cam = Camera("cam", look_at((0, 0, 5.0), (0, 0, 0), up=(0, 1, 0)), (4, 4), focal_length_mm=50.0,
                 film_width_mm=1.0, film_height_mm=1.0)
    emitter = quad((0, 0, 0), (5, 0, 0), (0, 5, 0))
    materials = [Material("lamp", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=1.0),
                 Material("glass tint", kind="null",
                          medium=MediumSpec("glass tint", absorb=[(DENSITY, COLOUR)]))]
    parts = [(*emitter, 0)]
    if with_slab:
        parts.append((*_box((0, 0, 2.0), (3, 3, THICKNESS_M / 2)), 1))
    # A point light (on the black lamp it lights nothing) turns on equiangular sampling toward lights, which a
    # medium that only absorbs must not use: each crossing would then weigh 0 or 2 exp(-σ_a d), not exp(-σ_a d).
    lights = [Light("bulb", "point", np.array([4.0, 0.0, 3.0]), power_w=50.0)] if point_light else []
    return make_scene(parts, materials, cam, lights)


@pytest.mark.parametrize("point_light", [False, True], ids=["area emitter", "and a point light"])
def test_slab_transmits_exp_minus_sigma_a_d_per_wavelength(point_light):
    films = []
    for with_slab in (False, True):
        with Renderer(_scene(with_slab, point_light), settings(samples=64, samples_per_pass=64, spectral_band_nm=10.0,
                                                  max_bounces=4)) as r:
            r.render_pass()
            films.append(r.spectral_film.mean().astype(np.float64).mean((0, 1)))
            centres, edges = r.spectral_film.centres_nm, None
    bare, through = films
    _, sigma_a = coefficient_spectra(MediumSpec("x", absorb=[(DENSITY, COLOUR)]))
    grid = np.asarray(VISIBLE_NM_GRID)
    half = (centres[1] - centres[0]) / 2
    expected = np.array([np.exp(-sigma_a[(grid >= c - half) & (grid <= c + half)] * THICKNESS_M).mean()
                         for c in centres])
    lit = bare > 1e-3 * bare.max()
    ratio = through[lit] / bare[lit]
    print("MEASURED transmittance / exp(-sigma_a d) per 10 nm band:", np.round(ratio / expected[lit], 4).tolist())
    print("MEASURED exp(-sigma_a d) range:", expected[lit].min(), expected[lit].max())
    assert expected[lit].max() / expected[lit].min() > 1.5  # a chromatic slab: the test can tell wavelengths apart
    assert ratio == pytest.approx(expected[lit], rel=5e-3)


def test_emitting_absorbing_slab_adds_its_closed_form_radiance():
    """A slab that absorbs (σ_a constant) and emits ε per metre, seen through its thickness d against black,
    shines ε (1 - exp(-σ_a d)) / σ_a: the same image, wavelength by wavelength, as an emitting surface of that
    strength in its place (same seed, same wavelengths)."""
    strength, density = 0.8, 2.0  # grey 0.5 absorbs half the density: σ_a = 1 per metre
    sigma_a = density * 0.5
    expected = strength * -np.expm1(-sigma_a * THICKNESS_M) / sigma_a
    cam = Camera("cam", look_at((0, 0, 5.0), (0, 0, 0), up=(0, 1, 0)), (4, 4), focal_length_mm=50.0,
                 film_width_mm=1.0, film_height_mm=1.0)
    glowing = Material("glow", kind="null", medium=MediumSpec(
        "glow", absorb=[(density, (0.5, 0.5, 0.5))], emission=[(strength, (1.0, 1.0, 1.0), None)]))
    panel = Material("panel", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=expected)
    images = []
    for scene in (make_scene([(*_box((0, 0, 2.0), (3, 3, THICKNESS_M / 2)), 0)], [glowing], cam),
                  make_scene([(*quad((0, 0, 2.0), (3, 0, 0), (0, 3, 0)), 0)], [panel], cam)):
        # Gaussian RGB wavelengths: in CIE mode the wavelength guide follows the panel's emission and not the
        # medium's (volume emission is not a light-sampled emitter), so the two renders would draw other wavelengths.
        with Renderer(scene, settings(samples=16, samples_per_pass=16, max_bounces=4,
                                      wavelength_mode="gaussian_rgb")) as r:
            r.render_pass()
            images.append(r.image_rgb().astype(np.float64))
    print(f"MEASURED emitting slab / closed form: {images[0].mean((0, 1)) / images[1].mean((0, 1))}")
    assert images[0] == pytest.approx(images[1], rel=2e-4)  # rays 0.3° off axis cross 1.00001 d
