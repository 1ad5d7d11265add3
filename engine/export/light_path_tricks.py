"""Cycles' Light Paths tricks a scene sets (``scene.cycles``: Clamp Direct / Indirect, Filter Glossy,
Reflective / Refractive Caustics, Max Bounces ▸ Diffuse / Glossy / Transmission / Volume) as
``tracer.path_tricks.LightPathTricks``, and the warnings for what Prism renders differently.

Only values the scene has set are read (``is_property_set``: changed in Cycles' Light Paths panel, or by a
script): Cycles' own defaults (Clamp Indirect 10, Filter Glossy 1, Diffuse and Glossy 4, Volume 0) bias or
darken every image, and Prism's default is the unbiased one limited by Max Bounces alone. A scene converted
from Cycles with these settings changed renders with them.
"""

from __future__ import annotations

from ..tracer.path_tricks import LightPathTricks

_FIELDS = (("sample_clamp_direct", "clamp_direct", float), ("sample_clamp_indirect", "clamp_indirect", float),
           ("blur_glossy", "filter_glossy", float), ("caustics_reflective", "caustics_reflective", bool),
           ("caustics_refractive", "caustics_refractive", bool), ("diffuse_bounces", "diffuse_bounces", int),
           ("glossy_bounces", "glossy_bounces", int), ("transmission_bounces", "transmission_bounces", int),
           ("volume_bounces", "volume_bounces", int))


def light_path_tricks(scene) -> LightPathTricks:
    tricks = LightPathTricks()
    cycles = getattr(scene, "cycles", None)
    if cycles is None:
        return tricks
    for blender, field, kind in _FIELDS:
        if cycles.is_property_set(blender):
            setattr(tricks, field, kind(getattr(cycles, blender)))
    return tricks


def light_path_trick_warnings(scene) -> list[str]:
    """The tricks set on ``scene`` that Prism does not render as Cycles does."""
    tricks = light_path_tricks(scene)
    out = []
    if not tricks.caustics_reflective and tricks.caustics_refractive:
        out.append(f"Scene '{scene.name}': Light Paths ▸ Caustics ▸ Reflective is off: Prism leaves out glossy "
                   "reflections after a diffuse bounce, as Cycles, but not the reflection of glass (Glass BSDF, "
                   "Principled transmission), which Cycles leaves out too.")
    return out
