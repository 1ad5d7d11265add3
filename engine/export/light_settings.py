"""Settings of a Blender light that Prism does not model: one warning each, naming the light."""

from __future__ import annotations

import math

_RAY_FLAGS = (("visible_diffuse", "Diffuse"), ("visible_glossy", "Glossy"), ("visible_transmission", "Transmission"),
              ("visible_volume_scatter", "Volume Scatter"))
_DEFAULT_MAX_BOUNCES = 1024


def is_portal(light_data) -> bool:
    """A Cycles portal: it only guides the world's sampling and emits nothing."""
    cycles = getattr(light_data, "cycles", None)
    return light_data.type == "AREA" and bool(getattr(cycles, "is_portal", False))


def light_warnings(obj) -> list[str]:
    """Warnings for the settings of light object ``obj`` that Prism ignores."""
    data = obj.data.original
    name = obj.name
    warnings = []
    hidden = [label for prop, label in _RAY_FLAGS if not getattr(obj, prop, True)]
    if hidden:
        warnings.append(f"Light '{name}': Ray Visibility {', '.join(hidden)} off is ignored; Prism lets every ray "
                        "see the light (only the Camera setting is honoured).")
    if not getattr(data, "use_shadow", True):
        warnings.append(f"Light '{name}': Cast Shadow off is ignored; Prism's lights always cast shadows.")
    cycles = getattr(data, "cycles", None)
    if cycles is not None and getattr(cycles, "max_bounces", _DEFAULT_MAX_BOUNCES) < _DEFAULT_MAX_BOUNCES:
        warnings.append(f"Light '{name}': Max Bounces {cycles.max_bounces} is ignored; the scene's bounce limit applies.")
    if getattr(data, "use_nodes", False) and data.node_tree is not None and len(data.node_tree.nodes) > 2:
        warnings.append(f"Light '{name}': its node tree is ignored; Prism uses the light's colour and power.")
    warnings += _collimated_area_warning(name, data)
    return warnings


def _collimated_area_warning(name: str, data) -> list[str]:
    """An area light narrower than Prism samples (Spread 0: a collimated beam). Cycles lights the patch
    straight in front of it (its light arrives along the normal only: ``area_light_spread_attenuation``'s
    zero-spread branch); Prism widens the beam to its narrowest spread, whose light reaches the same patch."""
    if data.type != "AREA":
        return []
    from ..tracer.lights.area import MIN_HALF_SPREAD

    spread = float(getattr(data, "spread", math.pi))
    if spread >= 2 * MIN_HALF_SPREAD:
        return []
    return [f"Light '{name}': Spread {math.degrees(spread):g}° makes a collimated beam (Cycles lights only the patch "
            f"straight in front of the light); Prism renders it with a Spread of {math.degrees(2 * MIN_HALF_SPREAD):.2g}°, "
            "the narrowest it samples, which lights the same patch but so noisily that it looks black at ordinary "
            "sample counts: set Spread to 1° or more (Object Data ▸ Light ▸ Spread)."]
