"""Settings shared by lights and materials that name a measured spectrum: a colour-science illuminant
key, a colour-checker patch, a spectrum file. Names are strings (as colour-science spells them) with
a search list, so a saved choice never depends on a list's order; the export checks them."""

from __future__ import annotations

from bpy.props import FloatProperty, StringProperty

from ..tracer.spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM
from ._common import TEMPERATURE_SUBTYPE, WAVELENGTH_SUBTYPE
from .file_path import BLEND_RELATIVE_PATH_OPTIONS

TEMPERATURE_RANGE_K = (1000.0, 40000.0)
DEFAULT_ILLUMINANT = "D65"
DEFAULT_PATCH = "ColorChecker N Ohta: dark skin"
FILE_FORMATS = "CSV (wavelength_nm, value), IES TM-27-14 XML (.spdx), Sekonic CSV or UPRTek text export"


def _matching(names, edit_text):
    text = (edit_text or "").strip().lower()
    return [name for name in names if text in name.lower()] if text else list(names)


def illuminant_search(self, context, edit_text):
    """colour-science's illuminant keys containing the typed text (imports colour-science once)."""
    from ..tracer.spectra.illuminants import illuminant_names

    try:
        return _matching(illuminant_names(), edit_text)
    except Exception:  # noqa: BLE001 - a search callback must never raise
        return []


def reflectance_search(self, context, edit_text):
    """Colour-checker patches (``"<checker>: <patch>"``) containing the typed text."""
    from ..tracer.spectra.measured_reflectance import reflectance_names

    try:
        return _matching(reflectance_names(), edit_text)
    except Exception:  # noqa: BLE001
        return []


def illuminant_property(description: str):
    return StringProperty(name="Illuminant", description=description, default=DEFAULT_ILLUMINANT,
                          search=illuminant_search, search_options=set())


def spectrum_file_property(name: str, description: str):
    return StringProperty(name=name, description=f"{description}: {FILE_FORMATS}", default="", subtype="FILE_PATH",
                          options=BLEND_RELATIVE_PATH_OPTIONS)


def temperature_property(description: str):
    return FloatProperty(name="Temperature", description=f"{description} (1000-40000 K render)", default=6500.0,
                         min=1.0, soft_min=TEMPERATURE_RANGE_K[0], soft_max=TEMPERATURE_RANGE_K[1],
                         subtype=TEMPERATURE_SUBTYPE)


def line_wavelength_property():
    return FloatProperty(name="Wavelength", description="Centre wavelength of the emission line in nm", default=550.0,
                         min=VISIBLE_MIN_NM, max=VISIBLE_MAX_NM, subtype=WAVELENGTH_SUBTYPE)


def line_width_property():
    return FloatProperty(name="Line Width", description="Full width at half maximum of the emission line in nm",
                         default=10.0, min=0.1, soft_max=100.0, max=470.0, subtype=WAVELENGTH_SUBTYPE)
