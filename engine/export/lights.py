"""Blender lights → ``tracer.scene.Light`` (power in Blender's watts, as Cycles).

The spectrum comes from ``Light.prism`` (``export.spectra``): the light's RGB colour (times a
blackbody where Blender's own Temperature is on, as Cycles multiplies them), a blackbody at a
colour temperature, a monochromatic line, a standard illuminant or a spectrum file. Strength is
Blender's own energy. Spread, sun angle, spot size and blend and the Camera ray visibility are
Cycles'; portals emit nothing (as in Cycles, where they only guide the world's sampling); settings
Prism does not model get one warning per light (``light_settings``).
"""

from __future__ import annotations

import math

import numpy as np

from ..tracer.errors import PrismInputError
from .float_range import check_light_value
from ..tracer.scene import Light, SpectrumSpec
from .animated import settings_source
from .light_settings import is_portal, light_warnings
from ..properties.light import COLOR_SOURCE_ITEMS
from .spectra import light_emission_source, shown_temperature

_AREA_SHAPES = {"SQUARE": "rectangle", "RECTANGLE": "rectangle", "DISK": "disk", "ELLIPSE": "disk"}


def light_spectrum(name: str, light_data) -> SpectrumSpec:
    """The light's spectrum specification; ``PrismInputError`` naming the light when it is invalid."""
    return light_emission_source(name, light_data).spec()


def _export_light(name: str, light_data, matrix_world) -> Light:
    matrix = np.array(matrix_world, dtype=np.float64)
    if not np.isfinite(matrix).all():
        raise PrismInputError(f"Light '{name}' has a non-finite transform: reset its location, rotation and scale.")
    # Blender 4.x's Exposure scales the energy by 2^exposure, as in Cycles and EEVEE.
    energy = float(light_data.energy) * 2.0 ** float(getattr(light_data, "exposure", 0.0))
    if not math.isfinite(energy) or energy < 0:
        raise PrismInputError(
            f"Light '{name}' has {'Strength' if light_data.type == 'SUN' else 'Power'} {energy:g}: "
            "Prism needs a finite value of 0 or more (negative light does not exist)."
        )
    setting = "Strength" if light_data.type == "SUN" else "Power"
    exposed = f"{setting} × 2^Exposure" if float(getattr(light_data, "exposure", 0.0)) else setting
    check_light_value(energy, f"Light '{name}'", exposed, " W/m²" if light_data.type == "SUN" else " W")
    axes = matrix[:3, :3]
    scale = np.linalg.norm(axes, axis=0)
    safe_scale = np.where(scale > 0, scale, 1.0)
    axis_u, axis_v, axis_z = (axes / safe_scale).T
    light = Light(
        name=name,
        kind=light_data.type.lower(),
        position=matrix[:3, 3].copy(),
        direction=-axis_z,
        axis_u=axis_u,
        axis_v=axis_v,
        spectrum=light_spectrum(name, light_data),
    )
    if light_data.type == "SUN":
        light.irradiance_w_m2 = energy
        light.sun_angle_rad = float(light_data.angle)
        return light
    light.power_w = energy
    if light_data.type in {"POINT", "SPOT"}:
        light.radius_m = float(light_data.shadow_soft_size)
        light.soft_falloff = bool(getattr(light_data, "use_soft_falloff", False))
    if light_data.type == "SPOT":
        light.spot_size_rad = float(light_data.spot_size)
        light.spot_blend = float(light_data.spot_blend)
    if light_data.type == "AREA":
        light.area_shape = _AREA_SHAPES[light_data.shape]
        light.spread_rad = float(getattr(light_data, "spread", math.pi))
        size_v = light_data.size if light_data.shape in {"SQUARE", "DISK"} else light_data.size_y
        light.size_u_m = float(light_data.size * scale[0])
        light.size_v_m = float(size_v * scale[1])
        if not (light.size_u_m > 0 and light.size_v_m > 0):
            raise PrismInputError(f"Area light '{name}' has zero size: give it a size above 0 (and a non-zero scale).")
        if not getattr(light_data, "normalize", True):
            # Unnormalised: the power is per square metre, so a larger light emits more.
            area = light.size_u_m * light.size_v_m * (math.pi / 4 if light.area_shape == "disk" else 1.0)
            light.power_w *= area
    return light


def temperature_warning(name: str, light_data) -> str | None:
    """Blender 4.4+'s light Temperature, where Prism renders something else than Cycles' Color × its colour:
    a Colour Source other than RGB (which sets the spectrum), or a temperature below Prism's blackbody range."""
    if not getattr(light_data, "use_temperature", False):
        return None
    temperature = float(light_data.temperature)
    source = light_data.prism.color_source
    if source != "RGB":
        label = next(item[1] for item in COLOR_SOURCE_ITEMS if item[0] == source)
        return (f"Light '{name}': Blender's Temperature ({temperature:g} K) is not used: Light ▸ Prism ▸ Colour "
                f"Source {label} sets the spectrum (Cycles renders the Color × the temperature's colour); set "
                "Colour Source to RGB to render the temperature.")
    shown = shown_temperature(temperature)
    if shown != temperature:
        return (f"Light '{name}': Temperature {temperature:g} K is below Prism's blackbody range; rendered at "
                f"{shown:g} K (the same brightness, a less deep red).")
    return None


def export_lights(depsgraph, warnings: list[str] | None = None) -> list[Light]:
    """Every visible light instance of the evaluated depsgraph (lights of power 0 are skipped)."""
    lights = []
    warned = set()
    warned_objects = set()
    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type != "LIGHT":
            continue
        data = obj.data.original
        warning = temperature_warning(obj.name, data)
        if warning and warnings is not None and data.name not in warned:
            warned.add(data.name)
            warnings.append(warning)
        if is_portal(obj.data.original):
            continue
        if warnings is not None and obj.original.name not in warned_objects:
            warned_objects.add(obj.original.name)
            warnings.extend(light_warnings(obj))
        # Settings from the original light unless animated (``animated``), placement from the instance.
        light = _export_light(obj.name, settings_source(obj.data), instance.matrix_world)
        light.visible_camera = bool(getattr(obj, "visible_camera", False))
        light.light_group = obj.lightgroup
        light.shadow_catcher = bool(getattr(obj, "is_shadow_catcher", True))  # lights a catcher's pass (default on)
        if light.power_w > 0 or light.irradiance_w_m2 > 0:
            lights.append(light)
    return lights
