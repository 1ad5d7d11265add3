"""The world's background as a light: the sphere distribution and the environment's sampling pass
chi-square tests and integrate to one (with a Mapping's Jacobian), texels keep their colour through the
spectral round trip, Blender's equirectangular layout, and renders stay unbiased with light sampling."""

import math

import numpy as np
import pytest
from scipy import stats

from engine.tracer.jit import kernel
from engine.tracer.lights import environment as env_module
from engine.tracer.lights.sphere_distribution import build_sphere_distribution, direction_pdf, sample_direction
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, World
from engine.tracer.spectra import cie
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.trapezoid import trapezoid

from ..tracer_scenes import look_at, make_scene, quad, settings, sphere_under_sky


@kernel
def _sample_many(dist, u, out, pdf, pdf_again):
    for i in range(u.shape[0]):
        d, p = sample_direction(dist, u[i, 0], u[i, 1])
        out[i, 0], out[i, 1], out[i, 2] = d
        pdf[i] = p
        pdf_again[i] = direction_pdf(dist, d)


@kernel
def _env_sample_many(env, u, out, pdf, pdf_again):
    for i in range(u.shape[0]):
        d, p = env_module.sample_li(env, u[i, 0], u[i, 1])
        out[i, 0], out[i, 1], out[i, 2] = d
        pdf[i] = p
        pdf_again[i] = env_module.pdf_li(env, d)


@kernel
def _env_pdf_many(env, d, pdf):
    for i in range(d.shape[0]):
        pdf[i] = env_module.pdf_li(env, (d[i, 0], d[i, 1], d[i, 2]))


@kernel
def _env_radiance_many(env, spectra, d, wavelengths, out):
    for i in range(d.shape[0]):
        env_module.radiance(env, spectra, (d[i, 0], d[i, 1], d[i, 2]), wavelengths, out[i])


def _uniform_directions(n, seed):
    u = np.random.default_rng(seed).random((n, 2))
    z = 1 - 2 * u[:, 0]
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(2 * np.pi * u[:, 1]), r * np.sin(2 * np.pi * u[:, 1]), z], axis=1)


def _chi2_p(observed, expected):
    keep = expected >= 5
    observed = np.append(observed[keep], observed[~keep].sum())
    expected = np.append(expected[keep], expected[~keep].sum())
    if expected[-1] == 0:
        observed, expected = observed[:-1], expected[:-1]
    return stats.chi2.sf(((observed - expected) ** 2 / expected).sum(), len(expected) - 1)


def _bins(d, rows, columns):
    """Equal-solid-angle bins: z in ``rows`` equal steps, azimuth in ``columns``."""
    z_bin = np.minimum(((1 - d[:, 2]) / 2 * rows).astype(int), rows - 1)
    phi = np.mod(np.arctan2(d[:, 1], d[:, 0]), 2 * np.pi)
    return z_bin * columns + np.minimum((phi / (2 * np.pi) * columns).astype(int), columns - 1)


def test_sphere_distribution_sampling_matches_its_cells():
    rng = np.random.default_rng(3)
    weights = rng.random((8, 16)) ** 3
    weights[2, 5:9] = 0.0
    dist = build_sphere_distribution(weights)
    n = 200_000
    d, pdf, again = np.empty((n, 3)), np.empty(n), np.empty(n)
    _sample_many(dist, rng.random((n, 2)), d, pdf, again)
    assert np.allclose(np.linalg.norm(d, axis=1), 1.0) and np.allclose(pdf, again, rtol=1e-9)
    # Each cell split in 2 x 2 sub-cells of equal solid angle (u halves, z halves).
    rows, columns = weights.shape
    z_edges = np.cos(np.linspace(0, np.pi, rows + 1))
    theta_row = np.minimum((np.arccos(np.clip(d[:, 2], -1, 1)) / np.pi * rows).astype(int), rows - 1)
    z_mid = 0.5 * (z_edges[theta_row] + z_edges[theta_row + 1])
    u = (np.pi - np.arctan2(d[:, 1], d[:, 0])) / (2 * np.pi)
    column2 = np.minimum((u * 2 * columns).astype(int), 2 * columns - 1)
    sub = (theta_row * 2 + (d[:, 2] < z_mid)) * 2 * columns + column2
    observed = np.bincount(sub, minlength=4 * rows * columns)
    expected = np.repeat(np.repeat(dist.cell_prob, 2, axis=0), 2, axis=1).ravel() / 4 * n
    assert observed[expected == 0].sum() == 0
    assert _chi2_p(observed.astype(float), expected) > 1e-3
    # The density is normalised over the sphere.
    uniform = _uniform_directions(400_000, 4)
    p = np.array([direction_pdf(dist, tuple(v)) for v in uniform[:4000]])
    assert np.mean(p) * 4 * np.pi == pytest.approx(1.0, abs=0.08)


def _random_image(height=16, width=32, seed=5, hot=True):
    rng = np.random.default_rng(seed)
    image = (0.2 + rng.random((height, width, 3))).astype(np.float32)
    if hot:
        image[3, 20] = (80.0, 60.0, 40.0)
    return image


def _mapping(rotation_deg=(20.0, -35.0, 70.0), scale=(1.0, 1.6, 0.7)):
    from scipy.spatial.transform import Rotation

    return Rotation.from_euler("xyz", rotation_deg, degrees=True).as_matrix() @ np.diag(scale)


@pytest.mark.parametrize("interpolation", ["linear", "closest"])
def test_environment_sampling_with_a_mapping_matches_its_density(interpolation):
    """With a hot texel, ∫ pdf dω = 1 and E[1/pdf] = 4π (the Jacobian of a rotating and stretching
    Mapping included); with a smooth image (whose density a quadrature integrates accurately), the
    sampled directions pass a chi-square test in equal-area world bins."""
    n = 200_000
    rng = np.random.default_rng(7)
    world = World(kind="image", image_rgb=_random_image(), strength=2.0, to_texture=_mapping(),
                  interpolation=interpolation)
    env, integral, _, _ = env_module.build_environment(world, SpectrumTable())
    assert integral > 0
    d, pdf, again = np.empty((n, 3)), np.empty(n), np.empty(n)
    _env_sample_many(env, rng.random((n, 2)), d, pdf, again)
    assert np.allclose(pdf, again, rtol=1e-6)
    uniform = _uniform_directions(400_000, 8)
    p_uniform = np.empty(len(uniform))
    _env_pdf_many(env, uniform, p_uniform)
    assert np.mean(p_uniform) * 4 * np.pi == pytest.approx(1.0, rel=0.02)
    assert np.mean(1.0 / pdf) / (4 * np.pi) == pytest.approx(1.0, rel=0.02)
    world.image_rgb = _random_image(hot=False)
    env = env_module.build_environment(world, SpectrumTable()).arrays
    _env_sample_many(env, rng.random((n, 2)), d, pdf, again)
    rows, columns, fine = 12, 24, 16
    zs = 1 - (np.arange(rows * fine) + 0.5) / (rows * fine) * 2
    phis = (np.arange(columns * fine) + 0.5) / (columns * fine) * 2 * np.pi
    zz, pp = np.meshgrid(zs, phis, indexing="ij")
    rr = np.sqrt(1 - zz**2)
    grid = np.stack([rr * np.cos(pp), rr * np.sin(pp), zz], -1).reshape(-1, 3)
    p_grid = np.empty(len(grid))
    _env_pdf_many(env, grid, p_grid)
    cell = 4 * np.pi / (rows * fine * columns * fine)
    expected = (p_grid.reshape(rows, fine, columns, fine).sum(axis=(1, 3)) * cell).ravel()
    expected *= n / expected.sum()
    observed = np.bincount(_bins(d, rows, columns), minlength=rows * columns).astype(float)
    assert _chi2_p(observed, expected) > 1e-3


def _texel_direction(row, column, height, width):
    theta = (row + 0.5) / height * np.pi
    phi = np.pi - 2 * np.pi * (column + 0.5) / width
    return np.array([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)])


def _rgb_of_spectra(values, wavelengths):
    xyz = trapezoid(values[..., None] * cie.cie_xyz_cmf(wavelengths), wavelengths, axis=-2) / cie.CMF_Y_INTEGRAL
    return cie.xyz_to_linear_rec709(xyz)


def test_texels_keep_their_colour_and_blenders_layout():
    """Seen through a texel's centre the background is the texel's RGB (to 1e-3, through its illuminant
    spectrum and the CIE observer); +X is the image centre, +Z the top row, +Y the left quarter."""
    height, width = 8, 16
    image = np.zeros((height, width, 3), np.float32)
    rng = np.random.default_rng(9)
    image[:] = rng.random((height, width, 3)) * np.array([3.0, 1.0, 0.5]) + 0.01
    spectra = SpectrumTable()
    world = World(kind="image", image_rgb=image, strength=1.5, interpolation="closest")
    env = env_module.build_environment(world, spectra).arrays
    arrays = spectra.arrays()
    wavelengths = np.arange(360.0, 830.5, 1.0)
    texels = [(0, 0), (3, 7), (7, 15), (4, 8), (2, 11)]
    d = np.array([_texel_direction(r, c, height, width) for r, c in texels])
    values = np.empty((len(d), len(wavelengths)))
    _env_radiance_many(env, arrays, d, wavelengths, values)
    rgb = _rgb_of_spectra(values, wavelengths) / np.asarray(__import__(
        "engine.tracer.spectra.rgb_to_spectrum", fromlist=["white_rgb"]).white_rgb())
    expected = 1.5 * np.array([image[r, c] for r, c in texels])
    assert np.allclose(rgb, expected, rtol=2e-3, atol=1e-4)
    # Blender's layout: u = 0.5 at +X, the top row at +Z, u = 0.25 at +Y.
    probe = np.zeros((height, width, 3), np.float32)
    probe[height // 2 - 1:height // 2 + 1, width // 2 - 1:width // 2 + 1] = 1.0  # around +X
    probe[0, :] = 2.0  # the zenith row
    probe[height // 2 - 1:height // 2 + 1, width // 4 - 1:width // 4 + 1] = 3.0  # around +Y
    env = env_module.build_environment(World(kind="image", image_rgb=probe), spectra).arrays
    arrays = spectra.arrays()
    out = np.empty((3, 1))
    _env_radiance_many(env, arrays, np.array([[1.0, 0, 0], [0, 0, 1.0], [0, 1.0, 0]]), np.array([560.0]), out)
    assert np.argsort(out[:, 0]).tolist() == [0, 1, 2] and out[0, 0] > 0


def test_linear_lookup_interpolates_between_texel_centres():
    image = np.zeros((4, 8, 3), np.float32)
    image[1, 2] = 1.0
    image[1, 3] = 3.0
    spectra = SpectrumTable()
    env = env_module.build_environment(World(kind="image", image_rgb=image), spectra).arrays
    arrays = spectra.arrays()
    a, b, half = (_texel_direction(1, c, 4, 8) for c in (2, 3, 2.5))
    out = np.empty((3, 1))
    _env_radiance_many(env, arrays, np.array([a, b, half]), np.array([560.0]), out)
    assert out[2, 0] == pytest.approx(0.5 * (out[0, 0] + out[1, 0]), rel=1e-3)


def _lit_floor(world, size=20, **kw):
    cam = Camera("cam", look_at((0, -3.0, 2.0), (0, 0, 0)), (size, size))
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    return make_scene([(*floor, 0)], [Material("grey", base_color=(0.5, 0.5, 0.5))], cam, world=world)


def test_light_sampling_is_unbiased_and_beats_bsdf_sampling_on_a_hot_spot():
    """A floor under a hot-spot image: light-sampled and BSDF-only renders agree (to their noise), and
    light sampling has far lower variance."""
    image = np.full((16, 32, 3), 0.2, np.float32)
    image[4:6, 10:12] = 400.0
    results = {}
    for sampled in (True, False):
        scene = _lit_floor(World(kind="image", image_rgb=image, sampled=sampled))
        with Renderer(scene, settings(samples=64, samples_per_pass=64, seed=3)) as r:
            r.render_pass()
            results[sampled] = (r.image_rgb().astype(np.float64), r.variance_rgb().astype(np.float64))
    (light, light_var), (bsdf, bsdf_var) = results[True], results[False]
    difference = (light - bsdf).mean()
    sigma = math.sqrt((light_var.sum() + bsdf_var.sum()) / light.size ** 2)
    assert abs(difference) < 4 * sigma
    assert bsdf_var.mean() > 20 * light_var.mean()


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_white_furnace_under_a_light_sampled_image(mode):
    """An albedo-1 sphere under a uniform-coloured image vanishes with light sampling and MIS."""
    scene = sphere_under_sky(size=12)
    colour = np.array([1.0, 0.5, 0.25], np.float32)
    scene.world = World(kind="image", image_rgb=np.ones((8, 16, 3), np.float32) * colour)
    with Renderer(scene, settings(samples=32, samples_per_pass=32, wavelength_mode=mode)) as r:
        r.render_pass()
        image = r.image_rgb()
        assert "HDRI (light-sampled)" in r.strategy
    scene.triangles = scene.triangles[:0]
    scene.triangle_material = scene.triangle_material[:0]
    with Renderer(scene, settings(samples=32, samples_per_pass=32, wavelength_mode=mode)) as r:
        r.render_pass()
        empty = r.image_rgb()
    assert np.allclose(image.mean((0, 1)) / empty.mean((0, 1)), 1.0, atol=0.01)
