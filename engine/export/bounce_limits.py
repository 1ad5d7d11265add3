"""Cycles' per-kind bounce limits a scene sets (``scene.cycles``: Light Paths ▸ Max Bounces ▸ Diffuse, Glossy,
Transmission, Volume), which Prism does not model: one warning each, saying what is rendered instead.

Prism limits a path by Render ▸ Light Paths ▸ Max Bounces alone (and cut-outs by Transparent:
``tracer.stages.bounces``). A per-kind limit below that cuts light Cycles would leave out, so where the scene has
set one lower (``is_property_set``: changed in Cycles' panel or by a script; Cycles' defaults are not the
scene's choice), Prism's image can be brighter there, never darker. Limits at or above Max Bounces change
nothing and are not warned.
"""

from __future__ import annotations

#: ``scene.cycles`` property → the name Cycles' Light Paths panel gives it, and what such a bounce is.
PER_KIND = (("diffuse_bounces", "Diffuse", "diffuse reflections"),
            ("glossy_bounces", "Glossy", "glossy reflections"),
            ("transmission_bounces", "Transmission", "transmissions"),
            ("volume_bounces", "Volume", "scatterings in volumes"))


def bounce_limit_warnings(scene, max_bounces: int) -> list[str]:
    """One warning per per-kind limit ``scene`` sets below Prism's ``max_bounces``."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None:
        return []
    out = []
    for name, label, what in PER_KIND:
        if not cycles.is_property_set(name):
            continue
        limit = int(getattr(cycles, name))
        if limit < max_bounces:
            out.append(f"Scene '{scene.name}': Light Paths ▸ Max Bounces ▸ {label} is {limit}, but Prism has no "
                       f"limit per kind of bounce: {what} go on up to Max Bounces ({max_bounces}), so the image can "
                       "be brighter than Cycles' where light takes more of them.")
    return out
