"""Nested media as Cycles 4.5 stacks volumes: a path is inside every closed mesh medium it has entered and not
left, and the medium it travels in is their sum, with the World's Volume (fog) added everywhere.

Cycles keeps a stack of the volumes a path is in (``kernel/integrator/volume_stack.h``): crossing a volume's
surface against its normal adds the object to the stack, crossing along it removes it, entering one already
there or leaving one not there changes nothing; the World's volume stays at the bottom of the stack, inside
meshes too; the shaders of every entry are evaluated and their closures added. So a marble of coloured glass
in a box of fog scatters and absorbs by the fog's coefficients plus the glass's, and the fog of the World
thickens a smoke cube. (Cycles 5 adds volume priorities, which 4.5 does not have.)

Prism's kernels read one ``MediaArrays`` row per segment, so each set of media a path can be in at once gets a
row of its own, holding the sum (``combined_spec``): a *state*. Which sets can occur is decided from the meshes'
bounding boxes (``overlapping_sets``: media whose boxes overlap pairwise, up to ``MAX_NESTED`` at once), and
crossing a medium's surface moves a path from one state's row to another's (``transitions``, read by the
kernels through ``MediaArrays.next_medium``). A set no state holds (more than ``MAX_NESTED`` media, or meshes
that leak) falls back to the medium just entered, as before media nested.

Sums of a grid medium (a Volume object, a baked density) and anything else are not made: delta and ratio
tracking need σ = density × one spectrum. Such a state keeps the grid medium's row alone (the export warns).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .phase_functions import HENYEY_GREENSTEIN

#: Mesh media a path is inside of at once, at most (the World's fog besides). Cycles' stack holds as many as the
#: scene's volume objects; deeper nesting is rare, and each depth multiplies the states overlapping meshes make.
MAX_NESTED = 4

#: States (sets of media) built at most: past this, larger sets fall back to the medium last entered.
MAX_STATES = 4096


def material_bounds(vertices, triangles, triangle_material, materials, motion_vertices=None) -> dict:
    """{material index: (lo, hi) float64 [3] each}: the box (world, m) of the triangles of every material that
    holds a medium, over every time step of ``motion_vertices`` ([S, V, 3], or None: the frame's only)."""
    material_of = np.asarray(triangle_material)
    steps = [np.asarray(vertices, np.float64)]
    if motion_vertices is not None:
        steps += [np.asarray(v, np.float64) for v in motion_vertices]
    bounds = {}
    for m, material in enumerate(materials):
        if getattr(material, "medium", None) is None:
            continue
        corners = np.asarray(triangles)[material_of == m].ravel()
        if not len(corners):
            continue
        points = np.concatenate([v[corners] for v in steps])
        bounds[m] = (points.min(axis=0), points.max(axis=0))
    return bounds


def overlapping_sets(bounds: dict) -> list[tuple[int, ...]]:
    """Sets (ascending tuples of material indices, 2 to ``MAX_NESTED`` long) of media whose ``bounds`` overlap
    pairwise (touching counts), smaller sets first, at most ``MAX_STATES`` of them."""
    keys = sorted(bounds)
    if len(keys) < 2:
        return []
    lo = np.array([bounds[k][0] for k in keys])
    hi = np.array([bounds[k][1] for k in keys])
    touch = np.all((lo[:, None, :] <= hi[None, :, :]) & (lo[None, :, :] <= hi[:, None, :]), axis=2)
    found, layer = [], [(i,) for i in range(len(keys))]
    for _ in range(MAX_NESTED - 1):
        layer = [s + (j,) for s in layer for j in range(s[-1] + 1, len(keys)) if touch[list(s), j].all()]
        if not layer:
            break
        found += layer[:MAX_STATES - len(found)]
        if len(found) >= MAX_STATES:
            break
    return [tuple(keys[i] for i in s) for s in found]


def scattering_weight(spec) -> float:
    """How much a medium scatters, as the Add Shader of volumes weighs phase lobes: Σ density × the colour's
    largest component over its scatter terms (``export.nodes.volumes``)."""
    return sum(max(float(d), 0.0) * max(float(c) for c in rgb) for d, rgb in spec.scatter)


def _lobes(spec):
    if spec.phase:
        return list(spec.phase)
    weight = scattering_weight(spec)
    return [(weight, HENYEY_GREENSTEIN, (float(spec.anisotropy),))] if weight > 0.0 else []


def combined_spec(specs):
    """The ``MediumSpec`` of homogeneous media added together, as Cycles adds the closures of every volume on
    its stack: scatter, absorption and emission terms summed; the phase function the mixture of each medium's,
    weighted by how much it scatters (one Henyey-Greenstein lobe where they all have the same anisotropy)."""
    first = specs[0]
    lobes = [lobe for spec in specs for lobe in _lobes(spec)]
    kinds = {(kind, tuple(parameters)) for _, kind, parameters in lobes}
    single = len(kinds) == 1 and next(iter(kinds))[0] == HENYEY_GREENSTEIN
    return replace(first, name=" + ".join(spec.name for spec in specs),
                   scatter=[t for spec in specs for t in spec.scatter],
                   absorb=[t for spec in specs for t in spec.absorb],
                   emission=[t for spec in specs for t in spec.emission],
                   anisotropy=next(iter(kinds))[1][0] if single else (first.anisotropy if not lobes else 0.0),
                   phase=[] if single or not lobes else lobes)


def transitions(states: dict, member_of: dict, rows: int) -> np.ndarray:
    """int32 [rows + 1, M, 2]: the row a path in row r (index r + 1; 0: vacuum, row -1) moves to when it crosses
    the surface of member j's medium (``member_of``: material index → j, its own row) leaving it (0) or entering
    it (1). ``states``: {frozenset of material indices: row}, holding the empty set and every single medium.
    Rows that are no state (a medium's own row where the World has fog) move as the state of that medium alone."""
    by_row = {row: members for members, row in states.items()}
    for material, j in member_of.items():
        by_row.setdefault(j, frozenset((material,)))
    table = np.empty((rows + 1, max(len(member_of), 1), 2), np.int32)
    for r in range(-1, rows):
        inside = by_row.get(r, frozenset())
        for material, j in member_of.items():
            left = inside - {material}
            table[r + 1, j, 0] = states.get(left, states[frozenset()])
            entered = inside | {material}
            if entered in states:
                table[r + 1, j, 1] = states[entered]
            elif len(inside) >= MAX_NESTED:  # Cycles ignores a volume entered past its stack's size
                table[r + 1, j, 1] = r
            else:  # the meshes leak, or past MAX_STATES: the medium just entered
                table[r + 1, j, 1] = states[frozenset((material,))]
    return table


def scene_bounds(scene) -> dict:
    """``material_bounds`` of a ``scene.Scene``'s media, over the shutter's time steps."""
    motion = getattr(scene, "motion", None)
    return material_bounds(scene.vertices, scene.triangles, scene.triangle_material, scene.materials,
                           None if motion is None else motion.vertices)


def scene_overlaps(scene) -> list[tuple[int, ...]]:
    """``overlapping_sets`` of the media of a ``scene.Scene``'s meshes, over the shutter's time steps."""
    return overlapping_sets(scene_bounds(scene))
