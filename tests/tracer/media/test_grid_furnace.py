"""Grid media rendered whole (delta tracking for paths, ratio tracking for shadow rays):

- an albedo-1 blob of density (white Volume Scatter × a Gaussian grid) inside a null box, under a white
  world: it scatters without absorbing, so the image stays at the world's luminance (a uniform world is not
  light-sampled: delta tracking, phase sampling and the boundary crossings; every weight stays exactly 1);
- the same blob inside a closed glowing emitter: light sampling from grid-medium vertices, the shadow rays'
  ratio tracking through the grid and across its boundary;
- a constant-density grid renders the homogeneous medium of the same coefficients (a chromatic medium that
  scatters and absorbs, lit by a sun: spectral MIS, absorption as a weight, ratio tracking), mean luminance
  within its noise.
"""

import numpy as np
import pytest

from engine.tracer.media.density_grid import DensityGrid
from engine.tracer.media.spec import MediumSpec
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec, World
from engine.tracer.spectra.rgb_to_spectrum import white_rgb

from ..tracer_scenes import look_at, make_scene, settings, uv_sphere

LUMINANCE = np.array([0.2126729, 0.7151522, 0.0721750])


def _box(center, half):
    """A closed box (outward normals) of half-extents ``half``."""
    c, h = np.asarray(center, float), np.asarray(half, float)
    corners = np.array([[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]) * h + c
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return corners, np.array([[f[0], f[1], f[2]] for f in faces] + [[f[0], f[2], f[3]] for f in faces])


def _blob(size=16, peak=4.0):
    """A Gaussian blob of density (``peak`` at the centre) on a ``size``³ grid spanning [-1, 1]³ m."""
    x = np.linspace(-1.0, 1.0, size)
    r2 = x[:, None, None] ** 2 + x[None, :, None] ** 2 + x[None, None, :] ** 2
    values = (peak * np.exp(-r2 / (2 * 0.35 ** 2))).astype(np.float32)
    step = 2.0 / (size - 1)
    index_to_world = np.array([[step, 0, 0, -1.0], [0, step, 0, -1.0], [0, 0, step, -1.0], [0, 0, 0, 1.0]])
    return DensityGrid(values, index_to_world, "blob")


def _luminance(r):
    img = r.image_rgb().astype(np.float64)
    stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) @ LUMINANCE ** 2 / img[..., 0].size)
    return img.mean((0, 1)) @ LUMINANCE, stderr


@pytest.mark.parametrize("g", [0.0, 0.7])
def test_white_grid_blob_vanishes_in_a_white_furnace(g):
    cam = Camera("cam", look_at((0, -4.0, 0), (0, 0, 0)), (10, 10), film_width_mm=20.0, film_height_mm=20.0)
    medium = MediumSpec("blob", scatter=[(1.0, (1.0, 1.0, 1.0))], anisotropy=g, density_grid=_blob())
    scene = make_scene([(*_box((0, 0, 0), (1.2, 1.2, 1.2)), 0)], [Material("blob", kind="null", medium=medium)],
                       cam, world=World(color=(1.0, 1.0, 1.0), strength=1.0))
    with Renderer(scene, settings(samples=16, samples_per_pass=16, max_bounces=256)) as r:
        r.render_pass()
        mean, stderr = _luminance(r)
        ratio = mean / (np.asarray(white_rgb()) @ LUMINANCE)
        print(f"MEASURED grid furnace g={g}: luminance / world = {ratio:.5f} (stderr {stderr:.5f})")
        assert ratio == pytest.approx(1.0, abs=2e-3)
        assert r.stats["nan_samples"] == 0


def test_white_grid_blob_vanishes_inside_a_glowing_enclosure():
    cam = Camera("cam", look_at((0, -2.5, 0), (0, 0, 0)), (10, 10), film_width_mm=30.0, film_height_mm=30.0)
    shell = uv_sphere((0, 0, 0), 3.0, rings=12, segments=24, inward=True)
    glow = Material("glow", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    means = []
    for with_blob in (False, True):
        parts, materials = [(*shell, 0)], [glow]
        if with_blob:
            parts.append((*_box((0, 0, 0), (1.1, 1.1, 1.1)), 1))
            materials.append(Material("blob", kind="null", medium=MediumSpec(
                "blob", scatter=[(1.0, (1.0, 1.0, 1.0))], anisotropy=0.3, density_grid=_blob(peak=3.0))))
        with Renderer(make_scene(parts, materials, cam), settings(samples=64, samples_per_pass=64,
                                                                  max_bounces=256)) as r:
            r.render_pass()
            mean, stderr = _luminance(r)
            means.append(mean)
            assert r.stats["nan_samples"] == 0
    ratio = means[1] / means[0]
    print(f"MEASURED grid blob in a glowing enclosure: luminance with / without = {ratio:.4f} "
          f"(stderr {stderr / means[0]:.4f})")
    assert ratio == pytest.approx(1.0, abs=0.01)


def test_constant_grid_renders_the_homogeneous_medium():
    density = 0.8
    cam = Camera("cam", look_at((0, -6.0, 1.0), (0, 0, 0)), (12, 12), film_width_mm=24.0, film_height_mm=24.0)
    sun = Light("sun", "sun", np.zeros(3), direction=np.array([0.3, 0.5, -0.8]) / np.linalg.norm([0.3, 0.5, -0.8]),
                irradiance_w_m2=3.0)
    scatter, absorb = [(1.0, (0.8, 0.6, 0.3))], [(1.0, (0.4, 0.5, 0.7))]
    # The grid's constant voxels cover the box: index 0 and 9 lie on its faces (voxels 0.25 m, box 2.25 m wide).
    constant = DensityGrid(np.full((10, 10, 10), density, np.float32),
                           np.array([[0.25, 0, 0, -1.125], [0, 0.25, 0, -1.125], [0, 0, 0.25, -1.125], [0, 0, 0, 1]]))
    results = []
    for spec in (MediumSpec("h", scatter=[(density * d, c) for d, c in scatter],
                            absorb=[(density * d, c) for d, c in absorb], anisotropy=0.4),
                 MediumSpec("g", scatter=scatter, absorb=absorb, anisotropy=0.4, density_grid=constant)):
        scene = make_scene([(*_box((0, 0, 0), (1.125, 1.125, 1.125)), 0)], [Material("m", kind="null", medium=spec)],
                           cam, lights=[sun], world=World(color=(0.2, 0.3, 0.5), strength=1.0))
        with Renderer(scene, settings(samples=128, samples_per_pass=128, max_bounces=64)) as r:
            r.render_pass()
            results.append(_luminance(r))
            assert r.stats["nan_samples"] == 0
    (homogeneous, h_err), (gridded, g_err) = results
    print(f"MEASURED constant grid / homogeneous medium: {gridded / homogeneous:.4f} "
          f"(stderr {np.hypot(h_err, g_err) / homogeneous:.4f})")
    assert abs(gridded - homogeneous) < 4.0 * np.hypot(h_err, g_err) + 0.002 * homogeneous
