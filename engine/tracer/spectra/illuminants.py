"""The standard illuminants colour-science ships (``SDS_ILLUMINANTS``): CIE A, D50-D75, E, FL1-FL12,
FL3.x, HP1-HP5, LED-B1 ... LED-V2, ISO 7589, ... — looked up by colour-science's own key."""

from __future__ import annotations

import difflib

import numpy as np

from ..errors import PrismInputError
from .cie import import_colour


def illuminant_names() -> list[str]:
    """colour-science's illuminant keys, in its order (e.g. ``"A"``, ``"D65"``, ``"FL2"``, ``"HP1"``)."""
    return list(import_colour().SDS_ILLUMINANTS.keys())


def canonical_illuminant(key: str, what: str = "Illuminant") -> str:
    """colour-science's spelling of ``key`` (case and surrounding spaces ignored), or a
    ``PrismInputError`` naming ``what`` and the nearest keys."""
    names = illuminant_names()
    wanted = str(key).strip()
    if wanted in names:
        return wanted
    folded = {name.lower(): name for name in names}
    if wanted.lower() in folded:
        return folded[wanted.lower()]
    close = difflib.get_close_matches(wanted, names, n=3, cutoff=0.5)
    hint = f"did you mean {', '.join(repr(c) for c in close)}?" if close else f"use one of {', '.join(names[:12])}, …"
    raise PrismInputError(f"{what}: '{key}' is not one of colour-science's standard illuminants; {hint}")


def illuminant_table(key: str, what: str = "Illuminant"):
    """(wavelength_nm, relative power) of illuminant ``key`` as colour-science tabulates it."""
    sd = import_colour().SDS_ILLUMINANTS[canonical_illuminant(key, what)]
    return np.asarray(sd.wavelengths, np.float64), np.asarray(sd.values, np.float64)
