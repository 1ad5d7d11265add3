"""Light linking and shadow linking (Blender 4.x, as Cycles renders them): which objects an emitter lights,
and which objects cast its shadows.

Sets, as Cycles keeps them (facts from Cycles' ``kernel/light/light.h`` ``light_link_object_match`` and
``kernel/bvh/util.h`` ``intersection_skip_shadow_link``): every object belongs to one *receiver light set*
and one *blocker shadow set* (set 0: the objects no linking singles out), at most 64 of each; every
emitter holds a 64-bit membership mask: bit s set means it lights the objects of receiver set s (casts
shadows from the objects of blocker set s). A mask of all ones (``ALL_SETS``) is an unlinked emitter.
The export (``engine/export/light_linking.py``) turns Blender's collections into these sets.

- **Light linking** applies to every ray but camera rays (Cycles tests ``PATH_RAY_VISIBILITY_CAMERA``): light
  sampling at a vertex counts a light only if it admits the vertex's object, and emission a BSDF-sampled
  ray finds counts only if the emitter admits the object of the path's last scattering vertex
  (``PathState.receiver``, Cycles' ``mis_ray_object``: null crossings keep it; -1 on camera rays). Both
  strategies drop the same emitters with the same pdfs, so MIS stays consistent.
- **Shadow linking**: a shadow ray toward a shadow-linked emitter ignores the objects outside its blocker
  sets (``stages.shadow``). Cycles skips shadow-linked emitters on the main path's indirect rays and finds
  them again with a dedicated shadow ray from the last vertex along the BSDF-sampled direction
  (``integrator/intersect_dedicated_light.h``), so their BSDF-sampled light also sees through the objects
  that do not block them. Prism instead counts a shadow-linked emitter by light sampling alone (MIS weight 1
  on the light sample, 0 on a BSDF-sampled hit after a non-delta lobe): the same expected image, noisier on
  glossy reflections of large shadow-linked lights. After a delta lobe (a mirror, glass) light sampling
  cannot reach the emitter, so the BSDF-sampled hit counts, seen along the main ray (objects that do not
  block that emitter still hide it there).

The kernels read ``LinkTables`` (``LightArrays.links``) only behind ``KernelSettings.light_linking`` /
``shadow_linking``; a scene without linking carries empty tables and runs the code it ran before.
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from .catcher_lights import excluded_from_catcher
from .jit import inlined, kernel
from .state import PREV_DELTA

ALL_SETS = -1  # int64 mask with every bit set: an emitter without linking
MAX_SETS = 64  # Cycles' LIGHT_LINK_SET_MAX: sets are bits of a 64-bit mask


@dataclass
class LightLinks:
    """The scene's linking, per object (parallel to ``Scene.object_names``) and per light (by name).

    ``object_receiver_set`` / ``object_blocker_set`` int64 [objects] (0..63); ``object_light_sets`` /
    ``object_shadow_sets`` int64 [objects]: the masks of each object as an emitter (its emissive
    triangles; ``ALL_SETS`` when unlinked); ``light_sets`` / ``light_shadow_sets``: masks of the Blender
    lights that are linked, by light name (lights not named are unlinked)."""

    object_receiver_set: np.ndarray
    object_blocker_set: np.ndarray
    object_light_sets: np.ndarray
    object_shadow_sets: np.ndarray
    light_sets: dict = field(default_factory=dict)
    light_shadow_sets: dict = field(default_factory=dict)

    @property
    def light_linking(self) -> bool:
        """Some emitter lights only some objects."""
        return bool((self.object_light_sets != ALL_SETS).any()) or any(m != ALL_SETS for m in self.light_sets.values())

    @property
    def shadow_linking(self) -> bool:
        """Some emitter's shadows come from only some objects."""
        return bool((self.object_shadow_sets != ALL_SETS).any()) or any(
            m != ALL_SETS for m in self.light_shadow_sets.values())


#: The kernels' view, per render triangle [T] (``receiver_set``, ``blocker_set``: its object's sets;
#: ``triangle_light_sets`` / ``triangle_shadow_sets``: its object's masks as an emitter) and per light row
#: (``row_light_sets`` / ``row_shadow_sets``); all int64, empty without linking.
LinkTables = namedtuple("LinkTables", "receiver_set blocker_set triangle_light_sets triangle_shadow_sets "
                                      "row_light_sets row_shadow_sets")


def no_links() -> LinkTables:
    empty = np.zeros(0, np.int64)
    return LinkTables(empty, empty, empty, empty, empty, empty)


def link_tables(links: LightLinks | None, triangle_objects, row_names) -> LinkTables:
    """``LinkTables`` of ``links`` for the render's triangles (``triangle_objects``: the object of each, or
    None) and light rows (``row_names``: the Blender light of each row, None for the emissive meshes, the
    world and its sun). Empty when nothing is linked."""
    if links is None or not (links.light_linking or links.shadow_linking) or triangle_objects is None:
        return no_links()
    objects = np.asarray(triangle_objects, np.int64)

    def per_triangle(values):
        return np.ascontiguousarray(np.asarray(values, np.int64)[objects]) if len(objects) else np.zeros(0, np.int64)

    rows_light = np.array([links.light_sets.get(name, ALL_SETS) if name else ALL_SETS for name in row_names]
                          or [ALL_SETS], np.int64)
    rows_shadow = np.array([links.light_shadow_sets.get(name, ALL_SETS) if name else ALL_SETS for name in row_names]
                           or [ALL_SETS], np.int64)
    return LinkTables(per_triangle(links.object_receiver_set), per_triangle(links.object_blocker_set),
                      per_triangle(links.object_light_sets), per_triangle(links.object_shadow_sets),
                      rows_light, rows_shadow)


@inlined
def in_sets(mask, member):
    """Whether set ``member`` (0..63) is in the 64-bit ``mask``."""
    return (mask >> member) & 1 != 0


@kernel
def emitter_sets(lights, emitter):
    """(light sets, shadow sets) of ``emitter``: a light row (< rows), or rows + an emissive triangle."""
    links = lights.links
    rows = lights.rows.shape[0]
    if emitter < rows:
        return links.row_light_sets[emitter], links.row_shadow_sets[emitter]
    return links.triangle_light_sets[emitter - rows], links.triangle_shadow_sets[emitter - rows]


@inlined
def hit_counts(state, i, settings, lights, emitter):
    """Whether emission from ``emitter`` (as ``emitter_sets`` numbers them) found by path ``i``'s
    BSDF-sampled ray counts: always without linking and on camera rays (receiver -1); else the emitter must
    light the last vertex's object, and a shadow-linked emitter counts only after a delta lobe (light
    sampling carries it otherwise). A shadow catcher's pass copy sees only the catcher's emitters
    (``catcher_lights``)."""
    if excluded_from_catcher(state, i, settings, lights, emitter):
        return False
    if not (settings.light_linking or settings.shadow_linking):
        return True
    receiver = state.receiver[i]
    if receiver < 0:
        return True
    light_sets, shadow_sets = emitter_sets(lights, emitter)
    if settings.light_linking and not in_sets(light_sets, receiver):
        return False
    return not (settings.shadow_linking and shadow_sets != ALL_SETS and not state.flags[i] & PREV_DELTA)


@inlined
def blocks(lights, shadow_sets, triangle):
    """Whether ``triangle`` casts the shadows of an emitter with blocker mask ``shadow_sets``."""
    return shadow_sets == ALL_SETS or in_sets(shadow_sets, lights.links.blocker_set[triangle])
