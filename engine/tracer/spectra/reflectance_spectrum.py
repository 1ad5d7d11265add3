"""Measured reflectances (colour-checker patches, spectrum files) from a ``scene.ReflectanceSpec``:
resampled once at every nanometre and interpolated linearly; beyond the data the end values continue
(a patch measured to 730 nm keeps its 730 nm reflectance, as colour-science extrapolates)."""

from __future__ import annotations

import numpy as np

from ..errors import PrismInputError
from .sampled import check_sampled, resample_1nm


class ReflectanceSpectrum:
    """``evaluate(wavelength_nm)`` → reflectance 0-1; ``first_nm`` and ``values`` (1 nm steps) for the table."""

    def __init__(self, spec, what="Reflectance"):
        if spec.kind == "measured":
            from .measured_reflectance import measured_reflectance

            wavelength_nm, values = measured_reflectance(spec.name, what)
            what = f"{what} '{spec.name}'"
        elif spec.kind == "tabulated" and spec.table is not None:
            wavelength_nm, values = spec.table.wavelength_nm, spec.table.values
            what = f"{what} '{spec.table.source}'" if spec.table.source else what
        else:
            raise PrismInputError(f"{what}: unknown reflectance kind '{spec.kind}'; use 'measured' or 'tabulated'.")
        self.first_nm, self.values = resample_1nm(*check_sampled(wavelength_nm, values, what, reflectance=True))

    def evaluate(self, wavelength_nm):
        """Reflectance at ``wavelength_nm`` (any shape)."""
        grid = self.first_nm + np.arange(len(self.values))
        return np.interp(np.asarray(wavelength_nm, dtype=np.float64), grid, self.values)
