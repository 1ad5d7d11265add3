"""A path under a subsurface closure: its random walk at the entry, and the vertex where it leaves.

At the entry (the shading stage sampled the closure, ``bsdf.subsurface_entry``) the walk runs at once
(``subsurface.walk``, Embree called from here). A path that leaves the object gets the exit as the hit of
its next bounce (``SUBSURFACE_EXIT``) and a ray queued as if it came from outside towards that point, as
Cycles pretends; the emission stage takes the stored hit instead of the ray's and adds no emission there.
At the exit the shading stage replaces the material by a Lambertian reflection of albedo 1 about the
smooth normal on the side the walk left through (Cycles' ``subsurface_shader_data_setup``): light sampling,
a diffuse bounce, no roulette (the path played it at the entry).

The walk's exit vertex is one step of Prism's loop but no bounce (``stages.bounces.count_crossing``): as in
Cycles, which counts nothing for the walk, the exit is shaded at the entry's bounce, so Max Bounces 0 still lights
skin through its exit. Not as in Cycles: the exit shades with the smooth normal, where Cycles takes a bumped
subsurface normal evaluated there.
"""

from __future__ import annotations

from ..bsdf.closure import C_KIND, C_NORMAL, C_WEIGHT, DIFFUSE
from ..jit import inlined
from ..materials.hit_inputs import object_row
from ..state import SUBSURFACE_EXIT
from ..subsurface.walk import random_walk
from .queue import push_ray

#: How far outside the exit the pretend ray starts (m); its hit is not used, only its direction.
PRETEND_DISTANCE_M = 1e-3


@inlined
def walk_under_surface(state, i, rays, geometry, triangle, row, spectral, p, ng, wi, next_rays, slot, scratch):
    """Path ``i`` entered the surface of ``triangle`` at ``p`` (geometric normal ``ng`` facing the view) along
    ``wi``: walk, and queue its exit at ``slot`` of ``next_rays``. Returns 1 if queued, 0 if the path ended
    under the surface."""
    own = object_row(geometry.attributes, triangle)
    hit, u, v, point, d = random_walk(rays, geometry.attributes, own, row, spectral, p, ng, wi, state.throughput[i],
                                      scratch)
    if hit < 0:
        return 0
    state.hit_triangle[i] = hit
    state.hit_u[i] = u
    state.hit_v[i] = v
    state.hit_t[i] = PRETEND_DISTANCE_M
    state.flags[i] |= SUBSURFACE_EXIT
    origin = (point[0] + PRETEND_DISTANCE_M * d[0], point[1] + PRETEND_DISTANCE_M * d[1],
              point[2] + PRETEND_DISTANCE_M * d[2])
    return push_ray(state, next_rays, slot, i, origin, (-d[0], -d[1], -d[2]))


@inlined
def lambertian_exit(rows, spectral):
    """The exit vertex's material: one Lambertian closure of albedo and tint 1 (returns the closure count)."""
    rows[0, :] = 0.0
    rows[0, C_KIND] = DIFFUSE
    rows[0, C_WEIGHT] = 1.0
    rows[0, C_NORMAL] = -1.0
    spectral[0, :, :] = 1.0
    return 1
