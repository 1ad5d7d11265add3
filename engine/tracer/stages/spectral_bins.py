"""Optional stage after ``film``: each path's spectral radiance as contributions to wavelength bands,
for a multispectral image (``spectral_film``). Runs only when spectral output is on.

Band b covers [first + b·width, first + (b+1)·width) nm. A wavelength sample λⱼ adds L(λⱼ) / (K p(λⱼ))
/ width to its band, p the full density (``cie`` mode: column j covers the j-th of K equal-probability
strata, so the K terms together estimate the integral; a path collapsed to its uniformly drawn hero
carries K× its radiance there and nothing elsewhere), so the expected value is the band's mean spectral
radiance.
"""

from __future__ import annotations

from ..jit import kernel


@kernel
def spectral_bins_kernel(state, count, first_nm, band_nm, bands, band_of, value):
    """``band_of[i, j]`` and ``value[i, j]`` for wavelength j of paths i < ``count``."""
    k = state.wavelength.shape[1]
    for i in range(count):
        for j in range(k):
            b = int((state.wavelength[i, j] - first_nm) / band_nm)
            band_of[i, j] = min(max(b, 0), bands - 1)
            radiance = state.radiance[i, j]
            density = k * state.wavelength_pdf[i, j]
            value[i, j] = radiance / (density * band_nm) if radiance != 0.0 and density > 0.0 else 0.0


@kernel
def spectral_splat(total, samples, pixels, band_of, value, count):
    """Add paths j < ``count`` to ``total[pixel, band]`` and count them in ``samples[pixel]``; returns how
    many wavelength contributions were dropped as non-finite."""
    dropped = 0
    k = value.shape[1]
    for j in range(count):
        p = pixels[j]
        samples[p] += 1
        for c in range(k):
            v = value[j, c]
            if v != v or v - v != 0.0:
                dropped += 1
                continue
            total[p, band_of[j, c]] += v
    return dropped
