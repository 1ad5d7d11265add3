"""Spectrum settings of lights and materials → the tracer's ``SpectrumSpec`` / ``ReflectanceSpec``.

A source is first read from Blender into plain values (``EmissionSource``, ``ReflectanceSource``,
hashable), then turned into a spec: the panels do the second step off the main thread to plot the
spectrum the render will use, exactly as the exporter does. Every error names the object, the setting
and the fix.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..properties.spectrum_sources import TEMPERATURE_RANGE_K
from ..tracer.errors import PrismInputError
from ..tracer.scene import ReflectanceSpec, SpectrumSpec
from ..tracer.spectra.wavelengths import VISIBLE_RANGE_NM


#: A light's Colour Source RGB with Blender's own Temperature checkbox on: its colour × the blackbody.
BLENDER_TEMPERATURE = "BLENDER_TEMPERATURE"
_EMISSION_FIELDS = {"BLACKBODY": ("temperature_k",), "MONOCHROMATIC": ("wavelength_nm", "width_nm"),
                    "ILLUMINANT": ("illuminant",), "FILE": ("path",), BLENDER_TEMPERATURE: ("temperature_k", "rgb")}
_REFLECTANCE_FIELDS = {"MEASURED": ("name",), "FILE": ("path",)}


def _only_used(cls, fields_of_source, owner, panel, source, values):
    """A source carrying only the values its kind uses: equal settings give equal (hashable) sources."""
    used = fields_of_source.get(source, ("rgb",))
    return cls(owner, panel, source, **{key: value for key, value in values.items() if key in used})


def _check_spectrum_scale(table, what: str) -> None:
    """An emission spectrum is scaled to luminance 1 (its strength sets the brightness), so only its shape
    counts; a peak near float64's limits (1e308, 1e-320) overflows or underflows in that scaling (a black
    light, numpy warnings): refuse it, saying to rescale the file."""
    from .float_range import LARGEST, SMALLEST

    peak = max(table.values)
    if not SMALLEST <= peak <= LARGEST:
        raise PrismInputError(f"{what} peaks at {peak:.3g}; Prism reads emission spectra peaking within {SMALLEST:g} to "
                              f"{LARGEST:g}: rescale the file (only its shape counts, the strength sets the brightness).")


@dataclass(frozen=True)
class EmissionSource:
    """What a light's or emissive material's spectrum is made of. ``owner`` names it in messages
    ("Light 'Lamp'"), ``panel`` where its settings are ("Light ▸ Prism"); ``source`` is the
    Colour Source enum (``RGB``/``COLOR``, ``BLACKBODY``, ``MONOCHROMATIC``, ``ILLUMINANT``, ``FILE``) or
    ``BLENDER_TEMPERATURE`` (a light's RGB colour × Blender's Temperature); ``path`` is absolute."""

    owner: str
    panel: str
    source: str
    rgb: tuple[float, float, float] = (1.0, 1.0, 1.0)
    temperature_k: float = 6500.0
    wavelength_nm: float = 550.0
    width_nm: float = 10.0
    illuminant: str = "D65"
    path: str = ""

    def spec(self) -> SpectrumSpec:
        """The tracer's spectrum; ``PrismInputError`` naming the owner, setting and fix."""
        where = f"{self.owner} ({self.panel})"
        if self.source == BLENDER_TEMPERATURE:  # Cycles: Color × the temperature's colour; Prism: a filtered Planck
            self._check_rgb()
            return SpectrumSpec(kind="blackbody", temperature_k=shown_temperature(self.temperature_k),
                                rgb=tuple(float(c) for c in self.rgb))
        if self.source == "BLACKBODY":
            low, high = TEMPERATURE_RANGE_K
            if not low <= self.temperature_k <= high:
                raise PrismInputError(
                    f"{self.owner}: blackbody temperature {self.temperature_k:g} K is outside {low:.0f}-{high:.0f} K; "
                    f"set {self.panel} ▸ Temperature within that range."
                )
            return SpectrumSpec(kind="blackbody", temperature_k=self.temperature_k)
        if self.source == "MONOCHROMATIC":
            low, high = VISIBLE_RANGE_NM
            if not low <= self.wavelength_nm <= high:
                raise PrismInputError(
                    f"{self.owner}: wavelength {self.wavelength_nm:g} nm is outside {low:.0f}-{high:.0f} nm; "
                    f"set {self.panel} ▸ Wavelength within it."
                )
            if not self.width_nm > 0:
                raise PrismInputError(f"{self.owner}: line width must be positive (got {self.width_nm:g} nm); "
                                      f"set {self.panel} ▸ Line Width.")
            return SpectrumSpec(kind="monochromatic", wavelength_nm=self.wavelength_nm, width_nm=self.width_nm)
        if self.source == "ILLUMINANT":
            from ..tracer.spectra.illuminants import canonical_illuminant

            key = canonical_illuminant(self.illuminant, f"{self.owner}: {self.panel} ▸ Illuminant")
            return SpectrumSpec(kind="illuminant", illuminant=key)
        if self.source == "FILE":
            from ..tracer.spectra.spectrum_files import read_spectrum_file

            if not self.path:
                raise PrismInputError(f"{self.owner}: no spectrum file is chosen; set {self.panel} ▸ Spectrum File.")
            table = read_spectrum_file(self.path, f"{where}: spectrum file")
            _check_spectrum_scale(table, f"{where}: spectrum file '{self.path}'")
            return SpectrumSpec(kind="tabulated", table=table)
        self._check_rgb()
        return SpectrumSpec(kind="rgb", rgb=tuple(float(c) for c in self.rgb))

    def _check_rgb(self) -> None:
        if not all(math.isfinite(c) and c >= 0 for c in self.rgb):
            raise PrismInputError(
                f"{self.owner}: its colour {self.rgb} has negative or non-finite values; pick a colour again."
            )


def shown_temperature(temperature_k: float) -> float:
    """Blender's light Temperature (800-20000 K) within Prism's blackbody range (1000-40000 K): 800-1000 K
    renders at 1000 K, warned by ``lights.temperature_warning``."""
    low, high = TEMPERATURE_RANGE_K
    return min(max(float(temperature_k), low), high)


@dataclass(frozen=True)
class ReflectanceSource:
    """What a material's base colour is: ``source`` ``COLOR`` (the RGB ``rgb``), ``MEASURED`` (colour-checker
    patch ``name``) or ``FILE`` (absolute ``path``)."""

    owner: str
    panel: str
    source: str
    rgb: tuple[float, float, float] = (0.8, 0.8, 0.8)
    name: str = ""
    path: str = ""

    def spec(self) -> ReflectanceSpec | None:
        """The measured reflectance (None for an RGB base colour); ``PrismInputError`` naming the fix."""
        if self.source == "MEASURED":
            from ..tracer.spectra.measured_reflectance import measured_reflectance

            measured_reflectance(self.name, f"{self.owner}: {self.panel} ▸ Measured Reflectance")
            return ReflectanceSpec(kind="measured", name=self.name.strip())
        if self.source == "FILE":
            from ..tracer.spectra.spectrum_files import read_spectrum_file

            if not self.path:
                raise PrismInputError(
                    f"{self.owner}: no reflectance file is chosen; set {self.panel} ▸ Reflectance File."
                )
            table = read_spectrum_file(self.path, f"{self.owner} ({self.panel}): reflectance file", reflectance=True)
            return ReflectanceSpec(kind="tabulated", table=table)
        return None


def absolute_path(path: str, data_block) -> str:
    """``//``-relative paths resolved against the data-block's library or the open .blend file."""
    import bpy

    return bpy.path.abspath(path, library=getattr(data_block, "library", None)) if path else ""


def light_emission_source(name: str, light_data) -> EmissionSource:
    """The spectrum settings of a Blender light (``Light.prism``; its colour for ``RGB``)."""
    settings = getattr(light_data, "prism", None)
    source = settings.color_source if settings is not None else "RGB"
    values = {"rgb": tuple(float(c) for c in light_data.color)}
    if settings is not None:
        values.update(temperature_k=float(settings.temperature_k), wavelength_nm=float(settings.wavelength_nm),
                      width_nm=float(settings.line_width_nm), illuminant=settings.illuminant,
                      path=absolute_path(settings.spectrum_file, light_data))
    if source == "RGB" and getattr(light_data, "use_temperature", False):  # Blender 4.4+'s own light temperature
        values["temperature_k"] = float(light_data.temperature)
        return _only_used(EmissionSource, _EMISSION_FIELDS, f"Light '{name}'", "Light", BLENDER_TEMPERATURE, values)
    return _only_used(EmissionSource, _EMISSION_FIELDS, f"Light '{name}'", "Light ▸ Prism", source, values)


def material_emission_source(material, emission_color) -> EmissionSource:
    """The emission spectrum settings of a material (``Material.prism``; the Principled emission colour
    for ``COLOR``)."""
    settings = material.prism
    values = dict(rgb=tuple(float(c) for c in emission_color), temperature_k=float(settings.emission_temperature_k),
                  wavelength_nm=float(settings.emission_wavelength_nm),
                  width_nm=float(settings.emission_line_width_nm), illuminant=settings.emission_illuminant,
                  path=absolute_path(settings.emission_file, material))
    return _only_used(EmissionSource, _EMISSION_FIELDS, f"Material '{material.name}'", "Material ▸ Prism ▸ Emission",
                      settings.emission_source, values)


def material_reflectance_source(material, base_color) -> ReflectanceSource:
    """The base colour settings of a material (``Material.prism``; the Principled base colour for ``COLOR``)."""
    settings = material.prism
    values = dict(rgb=tuple(float(c) for c in base_color), name=settings.measured_reflectance,
                  path=absolute_path(settings.reflectance_file, material))
    return _only_used(ReflectanceSource, _REFLECTANCE_FIELDS, f"Material '{material.name}'",
                      "Material ▸ Prism ▸ Base Colour", settings.reflectance_source, values)
