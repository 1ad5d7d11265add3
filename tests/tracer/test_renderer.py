"""End-to-end checks of the Renderer API on small scenes with closed forms."""

import numpy as np
import pytest

from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.renderer import Renderer
from engine.tracer.scene import SpectrumSpec
from engine.tracer.spectra.wavelengths import GaussianChannels
from engine.tracer.spectra.trapezoid import trapezoid

from .tracer_scenes import camera_rays, plane_under_point_light, settings


def _closed_form(scene, power, albedo, height):
    """I rho cos(theta) / (pi r^2) at each pixel centre of the plane z = 0."""
    w, h = scene.camera.resolution
    ys, xs = np.mgrid[0:h, 0:w]
    xy = np.stack([xs.ravel() + 0.5, ys.ravel() + 0.5], 1)
    o, d = camera_rays(scene.camera, xy)
    p = o - (o[:, 2] / d[:, 2])[:, None] * d
    to_light = np.array([0.0, 0.0, height]) - p
    r2 = (to_light**2).sum(1)
    cos = to_light[:, 2] / np.sqrt(r2)
    return (power / (4 * np.pi) * albedo * cos / (np.pi * r2)).reshape(h, w)


def _gaussian_white(s):
    """What a unit-luminance white spectrum gives per channel in gaussian_rgb mode."""
    lam = np.linspace(360.0, 830.0, 4701)
    spec = emission_spectrum(SpectrumSpec()).evaluate(lam)
    ch = GaussianChannels(s.channel_means_nm, s.channel_sigmas_nm)
    return trapezoid(ch.pdf(np.repeat(lam[:, None], 3, 1)) * spec[:, None], lam, axis=0)


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_point_light_on_diffuse_plane_matches_closed_form(mode):
    power, albedo, height = 100.0, 0.5, 2.0
    scene = plane_under_point_light(size=32, power=power, height=height, albedo=albedo)
    s = settings(wavelength_mode=mode, samples=8, samples_per_pass=8)
    r = Renderer(scene, s)
    r.render_pass()
    img = r.image_rgb().astype(np.float64)
    expected = _closed_form(scene, power, albedo, height)
    white = np.ones(3) if mode == "cie" else _gaussian_white(s)
    ratio = img.mean(axis=(0, 1)) / (expected.mean() * white)
    assert np.allclose(ratio, 1.0, atol=0.01), ratio
    assert r.stats["nan_samples"] == 0
    assert r.samples_done == 8
    assert r.variance_rgb().shape == img.shape and np.all(r.variance_rgb() >= 0)


def test_same_seed_same_image_and_rows_top_down():
    scene = plane_under_point_light(size=16)
    # move the light towards +Y (the top of the image: the camera's up is +Y)
    scene.lights[0].position = np.array([0.0, 0.5, 1.0])
    a = Renderer(scene, settings(samples=2, samples_per_pass=2, seed=7))
    b = Renderer(scene, settings(samples=2, samples_per_pass=2, seed=7, threads=1))
    a.render_pass()
    b.render_pass()
    assert np.array_equal(a.image_rgb(), b.image_rgb())
    img = a.image_rgb()
    assert img[:8].mean() > img[8:].mean()
    c = Renderer(scene, settings(samples=2, samples_per_pass=2, seed=8))
    c.render_pass()
    assert not np.array_equal(a.image_rgb(), c.image_rgb())


def test_progressive_passes_and_border():
    scene = plane_under_point_light(size=16)
    r = Renderer(scene, settings(samples=3, samples_per_pass=2, border=(4, 2, 12, 10)))
    r.render_pass()
    r.render_pass()
    assert r.samples_done == 3
    img = r.image_rgb()
    assert np.all(img[:2] == 0) and np.all(img[:, :4] == 0) and np.all(img[10:] == 0)
    assert np.all(img[2:10, 4:12] > 0)
    assert r.stats["rays_cast"] > 0 and isinstance(r.strategy, str)


def test_gaussian_pixel_filter_offsets_and_chunking():
    from scipy import stats

    from engine.tracer.cameras import make_camera
    from engine.tracer.chunk_pool import CHUNKS_PER_THREAD, MIN_CHUNK_PATHS, chunk_size
    from engine.tracer.stages.camera import filter_offset

    scene = plane_under_point_light(size=4)
    gaussian = make_camera(scene.camera, settings(pixel_filter="gaussian", filter_width_px=1.5)).data
    box = make_camera(scene.camera, settings()).data
    u = np.random.default_rng(0).random(100_000)
    off = np.array([filter_offset(gaussian, x) for x in u])
    assert np.all(np.abs(off - 0.5) <= 1.5) and off.mean() == pytest.approx(0.5, abs=0.01)
    # a Gaussian of sigma 0.5 px truncated at 3 sigma
    assert off.std() == pytest.approx(0.5 * np.sqrt(1 - 6 * stats.norm.pdf(3) / (1 - 2 * stats.norm.cdf(-3))),
                                      rel=0.02)
    assert np.array_equal([filter_offset(box, x) for x in u[:100]], u[:100])
    assert chunk_size(MIN_CHUNK_PATHS, 2) == MIN_CHUNK_PATHS and chunk_size(10**7, 2) == 1 << 16
    assert chunk_size(10**5, 2) == 10**5 // (2 * CHUNKS_PER_THREAD)
    assert chunk_size(10**5, 2, 3) % 3 == 0 and chunk_size(10, 2, 64) == MIN_CHUNK_PATHS


def test_dispersive_glass_out_of_range_is_reported():
    scene = plane_under_point_light(size=8)
    from engine.tracer.scene import Material

    scene.materials = [Material("sf11", kind="dielectric", glass="N-SF11")]
    r = Renderer(scene, settings(samples=16, samples_per_pass=16))
    r.render_pass()
    assert any("N-SF11" in w and "clamped" in w for w in r.stats["warnings"])
    assert r.stats["nan_samples"] == 0
