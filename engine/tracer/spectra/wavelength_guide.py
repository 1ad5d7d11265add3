"""The ``cie`` mode's wavelength density when the scene's light has spectral structure (emission lines,
fluorescent tubes, LEDs, measured spectra): it follows what the scene emits.

Density on 0.1 nm cells over 360-830 nm:

    p(λ) = (1 − f) · visible(λ) + f · Σₑ Pₑ Sₑ(λ) (x̄ + ȳ + z̄)(λ) / ∫ Σₑ Pₑ Sₑ (x̄ + ȳ + z̄)

with Pₑ the power of emitter e and Sₑ its luminance-normalised spectrum (``lights.emitters``), f =
``GUIDED_FRACTION``. A wavelength sample then carries about the same colour weight L / p wherever the
light is, so a spiky spectrum costs no more colour noise than a smooth one; the visible part keeps
every wavelength reachable. Lines are integrated exactly over each cell (a 0.1 nm line keeps its mass);
other spectra are read from the dense table at cell centres (exact for the piecewise-linear 1 nm
tables, whose knots are cell edges). The sampler draws a cell by its mass and a wavelength uniformly
in it, so the pdf it reports is exact.

Scenes lit only by smooth spectra (RGB colours, blackbodies) are not guided: the closed-form visible
density suits them and costs one logarithm per wavelength.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from .table import DENSE_COUNT, DENSE_START_NM, LINE, TABULATED
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM, visible_wavelength_pdf

GUIDED_CELL_NM = 0.1
GUIDED_FRACTION = 0.5

#: cdf float64 [C+1], mass float64 [C] (C cells of ``GUIDED_CELL_NM``), and for the render stats how
#: many emission lines and measured spectra it follows.
WavelengthGuide = namedtuple("WavelengthGuide", "cdf mass lines measured")


def cell_edges_nm() -> np.ndarray:
    cells = int(round((VISIBLE_MAX_NM - VISIBLE_MIN_NM) / GUIDED_CELL_NM))
    return np.linspace(VISIBLE_MIN_NM, VISIBLE_MAX_NM, cells + 1)


def _cell_integrals(spectra, sid, edges):
    """∫ S over each cell for spectrum row ``sid`` of ``spectra`` (a ``SpectrumArrays``)."""
    p = spectra.params[sid]
    if spectra.kind[sid] == LINE:
        from scipy.special import ndtr

        centre, sigma, lo, hi, scale = p[0], p[1], p[2], p[3], p[4]
        clipped = np.clip(edges, lo, hi)
        return scale * sigma * np.sqrt(2.0 * np.pi) * np.diff(ndtr((clipped - centre) / sigma))
    centres = 0.5 * (edges[1:] + edges[:-1])
    grid = DENSE_START_NM + np.arange(DENSE_COUNT)
    return np.interp(centres, grid, spectra.dense[sid]) * np.diff(edges)


def build_guide(spectra, emitters, response=None):
    """The ``WavelengthGuide`` for ``emitters`` ((spectrum id, power) pairs, see ``lights.emitters``) over
    the rows of ``spectra``, or None when no emitter has a line or a measured spectrum.
    ``response``: the CIE x̄ + ȳ + z̄ at the cell centres (computed when None)."""
    kinds = [int(spectra.kind[sid]) for sid, _ in emitters]
    lines = len({sid for (sid, _), k in zip(emitters, kinds) if k == LINE})
    measured = len({sid for (sid, _), k in zip(emitters, kinds) if k == TABULATED})
    if not (lines or measured):
        return None
    edges = cell_edges_nm()
    centres = 0.5 * (edges[1:] + edges[:-1])
    if response is None:
        from . import cie

        response = cie.cie_xyz_cmf(centres).sum(axis=1)
    emitted = np.zeros(len(centres))
    for sid, power in emitters:
        emitted += power * _cell_integrals(spectra, sid, edges)
    guided = emitted * response
    visible = visible_wavelength_pdf(centres)
    if not guided.sum() > 0.0:
        return None
    density = (1.0 - GUIDED_FRACTION) * visible / visible.sum() + GUIDED_FRACTION * guided / guided.sum()
    mass = density / density.sum()
    cdf = np.concatenate([[0.0], np.cumsum(mass)])
    cdf[-1] = 1.0
    return WavelengthGuide(cdf, mass, lines, measured)
