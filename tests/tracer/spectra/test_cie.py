import numpy as np
import pytest

from engine.tracer.spectra import cie
from engine.tracer.spectra.wavelengths import GaussianChannels, sample_visible_wavelengths
from engine.tracer.spectra.trapezoid import trapezoid
from helpers.spectral_oracles import gaussian_channel_samples_to_rgb


def test_cmf_table_values_and_range():
    xyz = cie.cie_xyz_cmf([555.0, 300.0, 900.0])
    assert xyz[0, 1] == pytest.approx(1.0, abs=2e-4)  # ybar peaks at 1 near 555 nm
    assert np.all(xyz[1:] == 0.0)
    assert cie.cie_xyz_cmf(np.zeros((2, 5))).shape == (2, 5, 3)
    assert cie.CMF_Y_INTEGRAL == pytest.approx(106.857, abs=1e-3)


def test_rec709_matrix_maps_d65_white_to_one():
    x, y = 0.3127, 0.3290
    white_xyz = np.array([x / y, 1.0, (1 - x - y) / y])
    assert np.allclose(cie.xyz_to_linear_rec709(white_xyz), 1.0, atol=1e-9)
    assert np.allclose(cie.linear_rec709_to_xyz(cie.xyz_to_linear_rec709(white_xyz)), white_xyz)


def test_constant_spectrum_estimate_converges_to_cmf_integral():
    rng = np.random.default_rng(3)
    n = 20000
    wavelength_nm, pdf = sample_visible_wavelengths(rng.random(n), 4)
    xyz = cie.spectral_samples_to_xyz(np.ones_like(wavelength_nm), wavelength_nm, pdf)
    table_nm = np.arange(360.0, 830.5, 1.0)
    expected = trapezoid(cie.cie_xyz_cmf(table_nm), table_nm, axis=0) / cie.CMF_Y_INTEGRAL
    assert expected[1] == pytest.approx(1.0)
    mean = xyz.mean(axis=0)
    stderr = xyz.std(axis=0, ddof=1) / np.sqrt(n)
    assert np.all(np.abs(mean - expected) < 4.0 * stderr), (mean, expected, stderr)
    assert np.all(stderr < 0.01)


def test_zero_pdf_samples_contribute_nothing():
    xyz = cie.spectral_samples_to_xyz(np.ones((1, 2)), np.array([[550.0, 550.0]]), np.array([[0.0, 0.0]]))
    assert np.all(xyz == 0.0)


def test_gaussian_channels_constant_spectrum_is_exactly_white():
    channels = GaussianChannels()
    wavelength_nm, pdf = channels.sample(np.random.default_rng(4).random((1000, 3)))
    rgb = gaussian_channel_samples_to_rgb(np.ones_like(wavelength_nm), wavelength_nm, pdf, channels)
    assert np.allclose(rgb, 1.0, rtol=1e-12, atol=0)


def test_monochromatic_rgb():
    rgb = cie.monochromatic_rgb([450.0, 530.0, 650.0, 300.0, 900.0])
    assert np.allclose(rgb[:3].max(axis=1), 1.0)
    assert np.argmax(rgb[0]) == 2 and np.argmax(rgb[1]) == 1 and np.argmax(rgb[2]) == 0
    assert np.all(rgb[3:] == 0.0) and np.all(rgb >= 0.0)


def test_check_rgb_rejects_bad_colours():
    from engine.tracer.errors import PrismInputError

    with pytest.raises(PrismInputError, match="NaN"):
        cie.check_rgb((np.nan, 0.0, 0.0), "Light 'Key'")
    with pytest.raises(PrismInputError, match="negative"):
        cie.check_rgb((-1.0, 0.0, 0.0), "Light 'Key'")
    with pytest.raises(PrismInputError, match="three"):
        cie.check_rgb((1.0, 0.0), "Light 'Key'")


def test_importing_the_physics_modules_is_cheap():
    """colour-science and scipy load lazily: importing the modules (as Blender's register might) pulls neither."""
    import subprocess
    import sys
    from pathlib import Path

    modules = "wavelengths trapezoid cie rgb_to_spectrum blackbody emission_spectrum glass conductors".split()
    code = (
        "import sys\n"
        + "".join(f"import engine.tracer.spectra.{m}\n" for m in modules)
        + "heavy = [m for m in ('colour', 'scipy') if m in sys.modules]\n"
        + "assert not heavy, heavy\n"
    )
    root = Path(__file__).resolve().parents[3]
    result = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_lazy_constants_import_by_name():
    from engine.tracer.spectra.cie import CMF_Y_INTEGRAL, XYZ_TO_LINEAR_REC709

    assert CMF_Y_INTEGRAL == cie.CMF_Y_INTEGRAL
    assert XYZ_TO_LINEAR_REC709.shape == (3, 3) and not XYZ_TO_LINEAR_REC709.flags.writeable
    with pytest.raises(AttributeError):
        cie.NOT_A_CONSTANT  # noqa: B018


def test_gaussian_channel_estimate_of_a_sloped_spectrum():
    """E[RGB_c] = ∫ L(λ) response_c(λ) dλ: for L(λ) = λ/500 that is the channel's truncated mean / 500."""
    from scipy import integrate

    channels = GaussianChannels()
    wavelength_nm, pdf = channels.sample(np.random.default_rng(6).random((20000, 3)))
    rgb = gaussian_channel_samples_to_rgb(wavelength_nm / 500.0, wavelength_nm, pdf, channels)
    for c in range(3):
        expected = integrate.quad(lambda x: x / 500.0 * channels.pdf(np.full(3, x))[c], 360.0, 830.0, points=[450, 550, 600])[0]
        stderr = rgb[:, c].std() / np.sqrt(len(rgb))
        assert abs(rgb[:, c].mean() - expected) < 4 * stderr


def test_uniform_table_lookup_matches_np_interp():
    wl = np.random.default_rng(7).uniform(350.0, 840.0, (50, 4))
    table_nm, xyz = cie._cmf_table()
    expected = np.stack([np.interp(wl, table_nm, xyz[:, c], left=0.0, right=0.0) for c in range(3)], axis=-1)
    assert np.allclose(cie.cie_xyz_cmf(wl), expected, rtol=0, atol=1e-15)
    assert np.all(np.isnan(cie.cie_xyz_cmf(np.nan)))
    assert cie.cie_xyz_cmf(830.0)[1] == xyz[-1, 1]
