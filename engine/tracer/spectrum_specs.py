"""How a scene names a spectrum before it is built: measured or tabulated values, an emitter's spectrum and a
measured reflectance (records of ``scene``; ``spectra.table`` turns them into the tables the kernels read)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SampledSpectrum:
    """Values measured or tabulated at increasing ``wavelength_nm`` (e.g. read from a spectrum file);
    ``source`` says where they came from, for messages (not part of the physics)."""

    wavelength_nm: tuple[float, ...]
    values: tuple[float, ...]
    source: str = ""


@dataclass(frozen=True)
class SpectrumSpec:
    """How an emitter's spectrum is defined.

    kind: ``"rgb"`` (linear Rec.709 triple, upsampled against D65),
    ``"blackbody"`` (``temperature_k``, 1000-40000 K; ``rgb`` other than white filters it as Blender's
    light Temperature × Color does: ``spectra.tinted_blackbody``), ``"monochromatic"``
    (a narrow line at ``wavelength_nm`` with full width ``width_nm``),
    ``"illuminant"`` (``illuminant``: a key of colour-science's ``SDS_ILLUMINANTS``,
    e.g. ``"FL2"``, ``"LED-B3"``, ``"HP1"``) or ``"tabulated"`` (``table``, a
    ``SampledSpectrum``, e.g. from a spectrum file).
    The spectrum is normalised so its luminance is that of the RGB white of the
    same strength (a tinted blackbody: that of the white blackbody through the tint);
    strength/power lives on the light, not here.
    """

    kind: str = "rgb"
    rgb: tuple[float, float, float] = (1.0, 1.0, 1.0)
    temperature_k: float = 6500.0
    wavelength_nm: float = 550.0
    width_nm: float = 10.0
    illuminant: str = ""
    table: SampledSpectrum | None = None


@dataclass(frozen=True)
class ReflectanceSpec:
    """A measured reflectance used instead of an RGB base colour.

    kind: ``"measured"`` (``name`` = ``"<colour checker>: <patch>"`` from colour-science's
    ``SDS_COLOURCHECKERS``, e.g. ``"ColorChecker N Ohta: dark skin"``) or ``"tabulated"``
    (``table``: values 0-1, e.g. from a spectrum file).
    """

    kind: str = "measured"
    name: str = ""
    table: SampledSpectrum | None = None
