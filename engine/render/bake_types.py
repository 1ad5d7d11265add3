"""What each of Blender's bake types asks Prism to render, and how its passes make the baked value.

Blender calls ``RenderEngine.bake`` with the bake type (``pass_type``, a string such as "COMBINED") and
the pass filter as an int of ``BakeSettings.pass_filter``'s bits. Prism bakes as Cycles 4.5 does
(``BlenderSession::bake`` and its pass set-up):

- Combined: the image's light; with some of Direct, Indirect, Diffuse, Glossy, Transmission or Emit off,
  the sum of the light passes left on: (Direct + Indirect) × Color of each scattering kind on, plus Emit.
- Diffuse, Glossy, Transmission: that kind's Direct and/or Indirect light, times its Color when Color is
  on (without it, the light divided by the colour, as Cycles' passes store it); Color alone: the colour.
- Emit: the surface's own emission. Normal: its world-space shading normal (bump and normal maps
  included: ``KernelSettings.shaded_normals``; Blender turns it into the bake's space and swizzle).
  Ambient Occlusion: the AO pass within World ▸ Ambient Occlusion ▸ Distance. Position: the point in
  world space.

Everything else is refused by name (``refusal``). Imports nothing heavy.
"""

from __future__ import annotations

from typing import NamedTuple

# ``BakeSettings.pass_filter`` bits as Blender hands them over (eBakePassFilter).
FILTER_EMIT = 1 << 1
FILTER_DIFFUSE = 1 << 2
FILTER_GLOSSY = 1 << 3
FILTER_TRANSMISSION = 1 << 4
FILTER_DIRECT = 1 << 6
FILTER_INDIRECT = 1 << 7
FILTER_COLOR = 1 << 8

#: The scattering kinds whose light passes Prism splits (``pass_table``): bake type and filter bit → prefix.
LOBES = {"DIFFUSE": (FILTER_DIFFUSE, "Diff"), "GLOSSY": (FILTER_GLOSSY, "Gloss"),
         "TRANSMISSION": (FILTER_TRANSMISSION, "Trans")}
#: What the Combined bake sums when its filter leaves everything on: the image itself.
WHOLE_IMAGE = "Combined"
#: Bake types Prism renders (Blender's identifiers) and their names in Render ▸ Bake ▸ Bake Type.
SUPPORTED = {"COMBINED": "Combined", "DIFFUSE": "Diffuse", "GLOSSY": "Glossy", "TRANSMISSION": "Transmission",
             "EMIT": "Emit", "NORMAL": "Normal", "AO": "Ambient Occlusion", "POSITION": "Position"}
#: Bake types written from one pass of the first surface (the bake type → Prism's pass).
FIRST_HIT_PASSES = {"EMIT": "Emit", "NORMAL": "Normal", "AO": "AO", "POSITION": "Position"}
#: Bake types Prism refuses, by their names in the Bake Type menu.
REFUSED = {"SHADOW": "Shadow", "UV": "UV", "ROUGHNESS": "Roughness", "ENVIRONMENT": "Environment"}


class BakeTerm(NamedTuple):
    """Passes added together (``WHOLE_IMAGE``: the rendered image), times the pass ``color`` (None: 1)."""

    light: tuple[str, ...]
    color: str | None = None


class BakeRecipe(NamedTuple):
    """How a bake type is rendered: the passes it needs, the terms whose sum is the baked value, and whether
    only the first surface matters (``first_hit_only``: no light needs to bounce)."""

    passes: tuple[str, ...]
    terms: tuple[BakeTerm, ...]
    first_hit_only: bool = False


def refusal(pass_type: str) -> str | None:
    """The message refusing bake type ``pass_type``, or None when Prism bakes it."""
    if pass_type in SUPPORTED:
        return None
    name = REFUSED.get(pass_type, pass_type)
    supported = ", ".join(SUPPORTED.values())
    return (f"Prism cannot bake '{name}' (Render ▸ Bake ▸ Bake Type): it bakes {supported}; "
            "choose one of these, or bake this type with Cycles.")


def _lobe_terms(prefix: str, pass_filter: int) -> tuple[BakeTerm, ...]:
    """One scattering kind's light as its Direct / Indirect / Color switches ask."""
    light = tuple(name for bit, name in ((FILTER_DIRECT, f"{prefix}Dir"), (FILTER_INDIRECT, f"{prefix}Ind"))
                  if pass_filter & bit)
    if not light:  # neither Direct nor Indirect: the colour (Cycles' DIFFUSE_COLOR pass, also with Color off)
        return (BakeTerm((f"{prefix}Col",)),)
    return (BakeTerm(light, f"{prefix}Col" if pass_filter & FILTER_COLOR else None),)


def _combined_terms(pass_filter: int) -> tuple[BakeTerm, ...]:
    everything = FILTER_DIRECT | FILTER_INDIRECT | FILTER_EMIT | FILTER_DIFFUSE | FILTER_GLOSSY | FILTER_TRANSMISSION
    if pass_filter & everything == everything:
        return (BakeTerm((WHOLE_IMAGE,)),)
    terms = []
    light_kinds = [name for bit, name in ((FILTER_DIRECT, "Dir"), (FILTER_INDIRECT, "Ind")) if pass_filter & bit]
    for bit, prefix in LOBES.values():
        if pass_filter & bit and light_kinds:
            terms.append(BakeTerm(tuple(prefix + kind for kind in light_kinds), f"{prefix}Col"))
    if pass_filter & FILTER_EMIT:
        terms.append(BakeTerm(("Emit",)))
    return tuple(terms)


def bake_recipe(pass_type: str, pass_filter: int) -> BakeRecipe:
    """The recipe of a supported bake type (``refusal`` is None) with Blender's ``pass_filter`` bits."""
    if pass_type == "COMBINED":
        terms = _combined_terms(pass_filter)
    elif pass_type in LOBES:
        terms = _lobe_terms(LOBES[pass_type][1], pass_filter)
    elif pass_type in FIRST_HIT_PASSES:
        name = FIRST_HIT_PASSES[pass_type]
        return BakeRecipe((name,), (BakeTerm((name,)),), first_hit_only=True)
    else:
        raise ValueError(f"bake type {pass_type} is refused, not baked")
    needed = {name for term in terms for name in (*term.light, term.color) if name and name != WHOLE_IMAGE}
    return BakeRecipe(tuple(sorted(needed)), terms)


def baked_value(recipe: BakeRecipe, image, passes: dict):
    """The baked value [h, w, 3] from the rendered ``image`` [h, w, 3] and ``passes`` (name → [h, w, C])."""
    import numpy as np

    total = np.zeros(image.shape[:2] + (3,), np.float64)
    for term in recipe.terms:
        light = sum((image if name == WHOLE_IMAGE else passes[name])[..., :3].astype(np.float64)
                    for name in term.light)
        total += light if term.color is None else light * passes[term.color][..., :3]
    return total
