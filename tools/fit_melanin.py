"""Fit the scales of the melanin power laws (``engine/tracer/spectra/melanin.py``) to Cycles' Rec.709 coefficients.

    PYTHONPATH=. python tools/fit_melanin.py

Prints each scale (per fibre diameter at 550 nm) and the relative error of the fitted spectrum's Rec.709
colour per channel."""

import numpy as np

from engine.tracer.spectra import melanin, rgb_to_spectrum

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec.709 luminance weights


def fit(exponent, target_rgb):
    """(scale, relative error per channel) of σ(λ) = scale (λ / 550 nm)^-exponent."""
    nm, kernel = rgb_to_spectrum._integration()
    target = np.asarray(target_rgb)
    base = (nm / melanin.REFERENCE_NM) ** -exponent @ kernel
    scale = np.sum(LUMINANCE * base * target) / np.sum(LUMINANCE * base * base)
    return scale, scale * base / target - 1.0


if __name__ == "__main__":
    for name, exponent, rgb in (("eumelanin", melanin.EUMELANIN_EXPONENT, melanin.CYCLES_EUMELANIN_RGB),
                                ("pheomelanin", melanin.PHEOMELANIN_EXPONENT, melanin.CYCLES_PHEOMELANIN_RGB)):
        scale, error = fit(exponent, rgb)
        print(f"{name}: scale {scale!r}, Rec.709 error {np.round(100 * error, 2)} %")
