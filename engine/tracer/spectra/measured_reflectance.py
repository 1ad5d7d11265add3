"""Measured reflectances of colour-checker patches (colour-science's ``SDS_COLOURCHECKERS``), named
``"<checker>: <patch>"``, e.g. ``"ColorChecker N Ohta: dark skin"``."""

from __future__ import annotations

import difflib

import numpy as np

from ..errors import PrismInputError
from .cie import import_colour

SEPARATOR = ": "


def _checkers() -> dict:
    """Checker name → {patch: sd}; colour-science's short aliases (``cc_ohta``) are left out."""
    checkers, seen = {}, set()
    for name, patches in import_colour().SDS_COLOURCHECKERS.items():
        if id(patches) not in seen:
            seen.add(id(patches))
            checkers[name] = patches
    return checkers


def reflectance_names() -> list[str]:
    """Every ``"<checker>: <patch>"``, checkers and patches in colour-science's order."""
    return [f"{checker}{SEPARATOR}{patch}" for checker, patches in _checkers().items() for patch in patches]


def checker_patches(checker: str) -> list[str]:
    """Full names of one checker's patches (e.g. the 24 of ``"ColorChecker N Ohta"``, in chart order)."""
    return [f"{checker}{SEPARATOR}{patch}" for patch in _checkers()[checker]]


def measured_reflectance(name: str, what: str = "Measured reflectance"):
    """(wavelength_nm, reflectance 0-1) of patch ``name``; ``PrismInputError`` naming ``what`` otherwise."""
    checkers = _checkers()
    checker, _, patch = str(name).partition(SEPARATOR.strip())
    checker, patch = checker.strip(), patch.strip()
    found = {c.lower(): c for c in checkers}.get(checker.lower())
    if found is not None:
        patches = {p.lower(): p for p in checkers[found]}
        if patch.lower() in patches:
            sd = checkers[found][patches[patch.lower()]]
            return np.asarray(sd.wavelengths, np.float64), np.asarray(sd.values, np.float64)
    close = difflib.get_close_matches(str(name), reflectance_names(), n=3, cutoff=0.6)
    hint = (f"did you mean {', '.join(repr(c) for c in close)}?" if close else
            f"write '<checker>{SEPARATOR}<patch>' with a checker among {', '.join(checkers)}.")
    raise PrismInputError(f"{what}: '{name}' is not a colour-checker patch colour-science knows; {hint}")
