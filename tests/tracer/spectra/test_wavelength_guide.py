"""The cie sampler follows the scene's emission: its table is the mixture of the visible density and
Σ P S (x̄ + ȳ + z̄) computed independently from the reference spectra, it draws wavelengths by that
table (chi-square) and reports the exact density, and smooth-lit scenes are left unguided."""

import numpy as np
import pytest
from scipy import stats

from engine.tracer.scene import SpectrumSpec
from engine.tracer.settings import RenderSettings
from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.wavelength_guide import GUIDED_CELL_NM, GUIDED_FRACTION, build_guide, cell_edges_nm
from engine.tracer.spectra.wavelength_sampling import build, sample_wavelengths
from engine.tracer.spectra.wavelengths import visible_wavelength_pdf

EMITTERS = [
    (SpectrumSpec(kind="illuminant", illuminant="FL2"), 40.0),
    (SpectrumSpec(kind="monochromatic", wavelength_nm=589.0, width_nm=0.3), 10.0),
    (SpectrumSpec(kind="rgb", rgb=(0.2, 0.4, 1.0)), 25.0),
]


def _guide(emitters=EMITTERS):
    table = SpectrumTable()
    rows = [(table.emission(spec), power) for spec, power in emitters]
    return build_guide(table.arrays(), rows)


def _reference_mass():
    """The mixture from the numpy reference spectra, lines integrated on a fine grid."""
    edges = cell_edges_nm()
    centres = 0.5 * (edges[1:] + edges[:-1])
    fine = np.linspace(edges[0], edges[-1], 20 * (len(edges) - 1) + 1)
    emitted = np.zeros(len(centres))
    for spec, power in EMITTERS:
        values = emission_spectrum(spec).evaluate(fine)
        area = np.concatenate([[0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * np.diff(fine))])
        emitted += power * np.diff(area[::20])
    guided = emitted * cie.cie_xyz_cmf(centres).sum(axis=1)
    visible = np.where(emitted > 0, visible_wavelength_pdf(centres), 0.0)
    mass = (1 - GUIDED_FRACTION) * visible / visible.sum() + GUIDED_FRACTION * guided / guided.sum()
    return mass / mass.sum()


def test_guide_is_the_power_weighted_emission_mixture():
    guide = _guide()
    assert (guide.lines, guide.measured) == (1, 1)
    reference = _reference_mass()
    assert np.abs(guide.mass - reference).sum() < 2e-3  # total variation distance
    line = (cell_edges_nm()[:-1] >= 587.0) & (cell_edges_nm()[1:] <= 591.0)
    assert guide.mass[line].sum() == pytest.approx(reference[line].sum(), rel=1e-3)


def test_sampler_draws_from_the_guide_chi_square_with_exact_pdfs():
    guide = _guide()
    ws = build(RenderSettings(wavelengths_per_path=4), guide)
    u = np.random.default_rng(7).random(100_000)
    lam = np.empty((len(u), 4))
    pdf = np.empty((len(u), 4))
    for i in range(len(u)):
        sample_wavelengths(ws, u[i], 0.0, 0.0, lam[i], pdf[i])
    cell = np.clip(((lam - 360.0) / GUIDED_CELL_NM).astype(int), 0, len(guide.mass) - 1)
    assert np.allclose(pdf, guide.mass[cell] / GUIDED_CELL_NM)
    cuts = np.searchsorted(guide.cdf, np.linspace(0, 1, 201)[1:-1])
    starts = np.unique(np.concatenate([[0], cuts]))
    expected = np.add.reduceat(guide.mass, starts)
    # Column j covers the j-th quarter of the cdf; the four columns together are distributed by the guide.
    observed = np.add.reduceat(np.bincount(cell.ravel(), minlength=len(guide.mass)), starts)
    keep = expected > 0
    assert stats.chisquare(observed[keep], expected[keep] / expected[keep].sum() * cell.size).pvalue > 1e-3
    for column in range(4):
        assert np.all((guide.cdf[cell[:, column]] <= (column + 1) / 4) & (guide.cdf[cell[:, column] + 1] >= column / 4))


def test_wavelengths_nothing_emits_are_never_drawn():
    table = SpectrumTable()
    lines = [(table.emission(SpectrumSpec(kind="monochromatic", wavelength_nm=nm, width_nm=2.0)), 1.0)
             for nm in (460.0, 580.0)]
    guide = build_guide(table.arrays(), lines)
    edges = cell_edges_nm()
    near = np.zeros(len(guide.mass), bool)
    for nm in (460.0, 580.0):
        near |= (edges[1:] > nm - 6.0) & (edges[:-1] < nm + 6.0)  # the lines' ±3 FWHM support
    assert guide.mass[~near].sum() == 0.0 and guide.mass[near].min() >= 0.0


def test_smooth_spectra_are_followed_too_and_a_dark_scene_keeps_the_visible_density():
    smooth = [(SpectrumSpec(kind="rgb", rgb=(1.0, 0.5, 0.2)), 1.0), (SpectrumSpec(kind="blackbody"), 3.0)]
    guide = _guide(smooth)
    assert (guide.lines, guide.measured, guide.smooth) == (0, 0, 2)
    assert _guide(smooth + [(SpectrumSpec(kind="illuminant", illuminant="D65"), 1.0)]).measured == 1
    assert _guide([]) is None


def test_cut_points_start_each_search_at_or_before_its_cell():
    guide = _guide()
    slots = len(guide.start)
    u = np.arange(slots) / slots
    assert np.all(guide.cdf[guide.start] <= u)
    assert np.all(np.diff(guide.start) >= 0)
