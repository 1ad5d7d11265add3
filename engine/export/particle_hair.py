"""Particle hair (a mesh's Particle System of type Hair, Render As "Path") → strands, as Cycles' Blender sync
reads them (``blender/curves.cpp``, ``ObtainCacheParticleData`` and ``ExportCurveSegments``).

For every particle system modifier switched on for this evaluation (Render in a render, Viewport in the
viewport) whose settings are Hair drawn as Path:

- Strands: the parents, and the children where there are any (with children on, Cycles renders only the
  children). The viewport takes Display Amount's share of the children (``display_percentage``), as Cycles.
- Points: (1 << steps) + 1 per strand, steps being Render Steps in a render and Viewport Display Steps in the
  viewport (plus Spiral kink's extra steps), read from Blender's path cache with ``ParticleSystem.co_hair``
  (world space) and taken into the object's space, so that instances of the emitter carry their hair.
- Radius: Hair Shape's Diameter Root and Tip times Radius Scale / 2, blended by Strand Shape along the strand
  (by length, Cycles' ``shaperadius``); Close Tip makes the last point's radius 0.
- Material: the settings' Material slot.

Strands the path cache has no points for (co_hair gives zeros) have no length and are left out; Cycles keeps
them as a point at the origin. Hair Info then reads them as Curves objects' strands (``hair_info``). The UV maps
and byte colour attributes the materials read are the emitter's at each strand's root (``emitter_roots``).
"""

from __future__ import annotations

import numpy as np

from .emitter_roots import root_values
from .hair import LocalHair


def hair_systems(obj, render: bool) -> list:
    """The particle systems of (evaluated) ``obj`` rendered as strands in this evaluation."""
    systems = []
    for modifier in getattr(obj, "modifiers", ()):
        if modifier.type != "PARTICLE_SYSTEM" or not (modifier.show_render if render else modifier.show_viewport):
            continue
        system = modifier.particle_system
        if system.settings.type == "HAIR" and system.settings.render_type == "PATH":
            systems.append(system)
    return systems


def hair_materials(obj, render: bool) -> list:
    """The materials of the slots ``obj``'s particle hair uses (Hair Shape's material slot of each system)."""
    slots = obj.material_slots
    return [slots[min(max(system.settings.material - 1, 0), len(slots) - 1)].material
            for system in hair_systems(obj, render) if len(slots)]


def uncarried_warning(name: str, uncarried) -> str:
    """The warning for particle hair of ``name`` whose material reads emitter attributes Cycles gives strands no
    value for (``emitter_roots``)."""
    reads = ", ".join(f"'{label}'" if label else "the default colour attribute" for _, label in sorted(uncarried))
    return (f"Particle hair on '{name}': its material reads the emitter's attribute {reads}, which strands do not "
            "carry: it reads black there, as in Cycles, which gives particle hair the emitter's UV maps and its "
            "byte colour attributes on face corners (by name) at each root, nothing else.")


def shape_radius(shape: float, root: float, tip: float, time: np.ndarray) -> np.ndarray:
    """Cycles' ``shaperadius``: the radius at ``time`` (0 root … 1 tip, by length) for Strand Shape ``shape``
    (-1 … 1; 0 linear)."""
    radius = 1.0 - np.clip(time, 0.0, 1.0)
    if shape < 0.0:
        radius = radius ** (1.0 + shape)
    elif shape > 0.0:
        radius = radius ** (1.0 / (1.0 - shape))
    return radius * (root - tip) + tip


def _system_strands(obj, system, render: bool, inverse: np.ndarray):
    """(points [N, S, 3] object space, per-point radius [N, S], material slot) of one system's strands."""
    settings = system.settings
    steps = (1 << (settings.render_step if render else settings.display_step)) + 1
    if settings.kink == "SPIRAL":
        steps += settings.kink_extra_steps
    parents, children = len(system.particles), len(system.child_particles)
    if not render:
        children = int(children * settings.display_percentage / 100.0)
    first = parents if settings.child_type != "NONE" and children > 0 else 0
    numbers = range(first, parents + children)
    world = np.array([[tuple(system.co_hair(obj, particle_no=n, step=s)) for s in range(steps)] for n in numbers],
                     dtype=np.float64).reshape(len(numbers), steps, 3)
    local = world @ inverse[:3, :3].T + inverse[:3, 3]
    along = np.concatenate([np.zeros((len(numbers), 1)),
                            np.cumsum(np.linalg.norm(np.diff(local, axis=1), axis=2), axis=1)], axis=1)
    length = along[:, -1:]
    time = np.divide(along, length, out=np.zeros_like(along), where=length > 0.0)
    half = settings.radius_scale * 0.5
    radius = shape_radius(settings.shape, half * settings.root_radius, half * settings.tip_radius, time)
    if settings.use_close_tip:
        radius[:, -1] = 0.0
    keep = length[:, 0] > 0.0
    return local[keep], radius[keep], settings.material - 1


def read_particle_hair(obj, render: bool, request=None) -> LocalHair | None:
    """Every strand of ``obj``'s particle hair, in its object space, with the emitter's UV maps and colour
    attributes ``request`` (``AttributeRequest``) names at each root; None when it has none."""
    inverse = np.linalg.inv(np.array(obj.matrix_world, dtype=np.float64))
    points, radii, counts, slots = [], [], [], []
    slot_count = max(len(obj.material_slots), 1)
    for system in hair_systems(obj, render):
        local, radius, slot = _system_strands(obj, system, render, inverse)
        if len(local) == 0:
            continue
        points.append(local.reshape(-1, 3))
        radii.append(radius.reshape(-1))
        counts.append(np.full(len(local), local.shape[1]))
        slots.append(np.full(len(local), min(max(slot, 0), slot_count - 1), np.int32))
    if not points:
        return None
    counts = np.concatenate(counts)
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    points = np.concatenate(points)
    colors, uvs, uncarried = _emitter_values(obj, points[offsets[:-1]], request)
    return LocalHair(points=points, radii=np.concatenate(radii), offsets=offsets, curve_slot=np.concatenate(slots),
                     slot_materials=[slot.material for slot in obj.material_slots],
                     attributes={slot: np.repeat(values, counts, axis=0) for slot, values in colors.items()},
                     uvs={slot: np.repeat(values, counts, axis=0) for slot, values in uvs.items()},
                     uncarried=tuple(uncarried))


def _emitter_values(obj, roots, request):
    if request is None or not (request.attributes or request.uvs):
        return {}, {}, []
    mesh = obj.to_mesh()
    if mesh is None:
        return {}, {}, []
    try:
        return root_values(mesh, roots, request)
    finally:
        obj.to_mesh_clear()
