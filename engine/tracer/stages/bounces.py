"""A path's bounces apart from the wavefront's depth, counted as Cycles counts them (``path_state_next``).

The bounce loop steps every path of a chunk together: at step ``depth`` each live path has travelled
``depth`` rays. Not every ray starts at a scattering, though:

- a **transparent bounce** goes straight through a cut-out (Transparent BSDF, alpha) or a free-standing film.
  Cycles counts these apart (Light Paths ▸ Max Bounces ▸ Transparent), not in Max Bounces;
- a **volume boundary** (a mesh whose material has a Volume but no Surface) is no bounce at all in Cycles: the
  ray goes on into or out of the medium, counted only against a sanity limit (``VOLUME_BOUNDS_MAX``);
- a **subsurface random walk** takes the step from its entry to its exit, and Cycles counts no bounce for it
  (its exit's reflection is the bounce).

``PathState.crossings`` int32 [n, 2] keeps, per path, the steps that were not scatterings (``STEPS``: all
three kinds) and the transparent bounces (``TRANSPARENT``). The path's bounce count is then ``depth`` minus its
steps. The sampler's dimensions stay per step (``sampler.bounce_slot(depth, ...)``), as Cycles advances its
``rng_offset`` at transparent bounces and volume boundaries too. The split of the render passes into direct and
indirect light counts bounces per path (``pass_writes.route_emission_kernel``), as Cycles' passes do.

A path whose bounces are used up (more than Max Bounces) still goes through cut-outs and films, as Cycles'
``PATH_RAY_TERMINATE_AFTER_TRANSPARENT``: the surface is shaded without light sampling, and the path ends
unless the sampled lobe went straight through (unbiased: the straight lobe is picked with its weight's share).
After Transparent Max Bounces + 1 transparent bounces (Cycles 4.5's count), the next surface ends the path after its
emission (``PATH_RAY_TERMINATE_ON_NEXT_SURFACE``).

Cycles' per-kind limits (Max Bounces ▸ Diffuse, Glossy, Transmission, Volume, where the scene sets one below Max
Bounces: ``KernelSettings.kind_limits``) use up a path's bounces the same way, counted as ``path_state_next`` counts
them in ``PathState.light_path``: a reflection off a diffuse lobe, off any other lobe (glossy), any transmission, a
scattering in a medium. Like Max Bounces, Cycles' kernel limit is the setting + 1 (``bounces_left``).
"""

from __future__ import annotations

from ..jit import inlined, kernel
from ..materials.light_path import DIFFUSE, GLOSSY, TRANSMISSION, VOLUME

#: ``PathState.crossings`` columns: steps that were not scatterings; of them, transparent bounces.
STEPS, TRANSPARENT = 0, 1
CROSSINGS = 2

#: Volume boundaries a path may cross (Cycles' ``VOLUME_BOUNDS_MAX``): a guard against a ray stuck on a surface.
VOLUME_BOUNDS_MAX = 1024


@kernel
def step_limit(max_bounces, transparent_max_bounces):
    """Steps of the bounce loop: every bounce, every transparent bounce and the volume boundaries a path may take,
    the camera ray, and the ray that only finds the emission past the last bounce."""
    return max_bounces + transparent_max_bounces + VOLUME_BOUNDS_MAX + 3


@inlined
def start_counts(state, i):
    """A new camera path: no steps skipped, no transparent bounce."""
    state.crossings[i, STEPS] = 0
    state.crossings[i, TRANSPARENT] = 0


@inlined
def path_bounce(state, i, depth):
    """The scatterings path ``i`` has made before the vertex it meets at step ``depth``."""
    return depth - state.crossings[i, STEPS]


@inlined
def ends_at_next_surface(state, i, settings):
    """Cycles' PATH_RAY_TERMINATE_ON_NEXT_SURFACE: the path has made its last transparent bounce. Cycles 4.5 sets the
    flag once a path has made Transparent Max Bounces + 1 of them (its kernel limit is the setting + 1, as Max
    Bounces' is), measured: five stacked cut-outs pass light at Transparent Max Bounces 4, none at 3."""
    return state.crossings[i, TRANSPARENT] > settings.transparent_max_bounces


@inlined
def count_crossing(state, i, transparent):
    """Path ``i`` took a step that is no scattering: straight through a surface (a transparent bounce), or
    (``transparent`` False) through a volume's boundary or under a surface (a subsurface random walk)."""
    state.crossings[i, STEPS] += 1
    if transparent:
        state.crossings[i, TRANSPARENT] += 1


@inlined
def shadow_crossings(state, i, settings):
    """The cut-outs and films a shadow ray from path ``i``'s vertex may cross: Transparent Max Bounces less the
    transparent bounces the path made (Cycles' ``integrate_shadow_max_transparent_hits``; volume boundaries do not
    count). One more blocks the ray."""
    return max(settings.transparent_max_bounces - state.crossings[i, TRANSPARENT], 0)


@inlined
def bounces_left(state, i, bounce, settings):
    """Whether path ``i``, having made ``bounce`` scatterings, may scatter again at its next vertex: within Max
    Bounces and within each per-kind limit (a count may equal its setting: Cycles ends a path once a count reaches
    the setting + 1)."""
    if bounce > settings.max_bounces:
        return False
    if not settings.kind_limits:
        return True
    record = state.light_path[i]
    diffuse, glossy, transmission, volume = settings.bounce_limits
    return (record[DIFFUSE] <= diffuse and record[GLOSSY] <= glossy and record[TRANSMISSION] <= transmission
            and record[VOLUME] <= volume)
