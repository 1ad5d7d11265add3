"""Blender's Light Path node: what kind of ray reached the point a material is evaluated at, as Cycles
defines it (``svm_node_light_path`` and ``path_state_next``).

A path keeps its record in ``PathState.light_path`` int32 [n, RECORD]: the *visibility* bits of the ray it
travels on (one of camera, diffuse, glossy (singular lobes count as glossy), volume scatter; transmit
with diffuse or glossy when it passed through the surface; reflect and singular as Cycles' path flags) and
its bounce counts (all, diffuse reflections, glossy reflections, transmissions, transparent crossings, volume
scatterings).
A scattering (``after_scattering``) sets them as Cycles' ``path_state_next``; a transparent crossing (a
cut-out, a film) counts one transparent bounce and keeps the ray's kind, as in Cycles, and the ray's
length goes on from where it started (``PathState.ray_travelled``).

Before a material program runs, the caller writes the node's outputs into the last ``FIELDS`` registers
of the register file (``regs``; ``state.new_shading_scratch`` reserves them): the path's own record for a
ray that hit the surface, the shadow ray's (only Is Shadow Ray, one bounce further) for a shadow ray
crossing a cut-out, and the emission's (no kind, one bounce further) for a point light sampling picked on
an emitter. The ``LIGHT_PATH`` instruction copies one of them. Everything here runs only in scenes whose
materials read the node (``KernelSettings.light_path``) or that limit bounces by kind (``kind_limits``: the
counts alone, ``stages.bounces.bounces_left``).
"""

from __future__ import annotations

from ..bsdf.closure import SAMPLED_DELTA, SAMPLED_DIFFUSE, SAMPLED_TRANSMISSION
from ..jit import inlined, kernel

#: The node's outputs, in Blender's order (``ShaderNodeLightPath.outputs``): the instruction's mode.
OUTPUTS = ("Is Camera Ray", "Is Shadow Ray", "Is Diffuse Ray", "Is Glossy Ray", "Is Singular Ray",
           "Is Reflection Ray", "Is Transmission Ray", "Is Volume Scatter Ray", "Ray Length", "Ray Depth",
           "Diffuse Depth", "Glossy Depth", "Transparent Depth", "Transmission Depth")
(IS_CAMERA, IS_SHADOW, IS_DIFFUSE, IS_GLOSSY, IS_SINGULAR, IS_REFLECTION, IS_TRANSMISSION, IS_VOLUME_SCATTER,
 RAY_LENGTH, RAY_DEPTH, DIFFUSE_DEPTH, GLOSSY_DEPTH, TRANSPARENT_DEPTH, TRANSMISSION_DEPTH) = range(len(OUTPUTS))
FIELDS = len(OUTPUTS)  # registers reserved at the end of the register file

#: ``PathState.light_path`` columns (VOLUME: scatterings in media, which the node does not show; Cycles' Max
#: Bounces ▸ Volume limits them).
VISIBILITY, BOUNCE, DIFFUSE, GLOSSY, TRANSMISSION, TRANSPARENT, VOLUME = range(7)
RECORD = 7

#: Visibility bits (Cycles' PATH_RAY_VISIBILITY_* and the REFLECT / SINGULAR path flags).
CAMERA, DIFFUSE_RAY, GLOSSY_RAY, TRANSMIT, VOLUME_SCATTER, REFLECT, SINGULAR, SHADOW = 1, 2, 4, 8, 16, 32, 64, 128


@inlined
def start_camera_ray(state, i):
    """A camera ray: camera visibility, no bounces."""
    record = state.light_path[i]
    record[:] = 0
    record[VISIBILITY] = CAMERA
    state.ray_travelled[i] = 0.0


@inlined
def after_scattering(state, i, sampled):
    """The path scattered off a surface by a lobe that gave ``sampled`` (``bsdf.closure.SAMPLED_*``)."""
    record = state.light_path[i]
    record[BOUNCE] += 1
    state.ray_travelled[i] = 0.0
    visibility = 0
    if sampled & SAMPLED_TRANSMISSION:
        visibility = TRANSMIT
        record[TRANSMISSION] += 1
    else:
        visibility = REFLECT
        if sampled & SAMPLED_DIFFUSE:
            record[DIFFUSE] += 1
        else:
            record[GLOSSY] += 1
    if sampled & SAMPLED_DIFFUSE:
        visibility |= DIFFUSE_RAY
    else:
        visibility |= GLOSSY_RAY
        if sampled & SAMPLED_DELTA:
            visibility |= SINGULAR
    record[VISIBILITY] = visibility


@inlined
def after_transparent(state, i, counted):
    """The path went straight through a cut-out or a film (``counted``: one transparent bounce more) or a volume's
    boundary (no bounce at all, as in Cycles): same kind of ray, and the length so far carried on."""
    if counted:
        state.light_path[i, TRANSPARENT] += 1
    state.ray_travelled[i] += state.hit_t[i]


@inlined
def after_volume_scatter(state, i):
    """The path scattered in a medium."""
    record = state.light_path[i]
    record[BOUNCE] += 1
    record[VOLUME] += 1
    record[VISIBILITY] = VOLUME_SCATTER
    state.ray_travelled[i] = 0.0


@kernel
def _write(regs, visibility, bounce, diffuse, glossy, transparent, transmission, ray_length):
    b = regs.shape[0] - FIELDS
    regs[b + IS_CAMERA] = 1.0 if visibility & CAMERA else 0.0
    regs[b + IS_SHADOW] = 1.0 if visibility & SHADOW else 0.0
    regs[b + IS_DIFFUSE] = 1.0 if visibility & DIFFUSE_RAY else 0.0
    regs[b + IS_GLOSSY] = 1.0 if visibility & GLOSSY_RAY else 0.0
    regs[b + IS_SINGULAR] = 1.0 if visibility & SINGULAR else 0.0
    regs[b + IS_REFLECTION] = 1.0 if visibility & REFLECT else 0.0
    regs[b + IS_TRANSMISSION] = 1.0 if visibility & TRANSMIT else 0.0
    regs[b + IS_VOLUME_SCATTER] = 1.0 if visibility & VOLUME_SCATTER else 0.0
    regs[b + RAY_LENGTH] = ray_length
    regs[b + RAY_DEPTH] = bounce
    regs[b + DIFFUSE_DEPTH] = diffuse
    regs[b + GLOSSY_DEPTH] = glossy
    regs[b + TRANSPARENT_DEPTH] = transparent
    regs[b + TRANSMISSION_DEPTH] = transmission


@inlined
def path_ray(regs, state, i, ray_length):
    """The node as seen by path ``i``'s ray, which travelled ``ray_length`` m from its last crossing to the point."""
    r = state.light_path[i]
    _write(regs, r[VISIBILITY], r[BOUNCE], r[DIFFUSE], r[GLOSSY], r[TRANSPARENT], r[TRANSMISSION],
           state.ray_travelled[i] + ray_length)


@inlined
def shadow_ray(regs, state, i, layers, ray_length):
    """The node as seen by a shadow ray of path ``i`` that crossed ``layers`` cut-outs or films before this
    one: Is Shadow Ray only, Ray Depth one bounce further (Cycles). ``ray_length`` counts from the last layer
    crossed (Cycles: from the shading point)."""
    r = state.light_path[i]
    _write(regs, SHADOW, r[BOUNCE] + 1, r[DIFFUSE], r[GLOSSY], r[TRANSPARENT] + layers, r[TRANSMISSION], ray_length)


@inlined
def emission_sample(regs, state, i):
    """The node as seen when light sampling from path ``i``'s vertex evaluates an emitter: no ray kind, Ray
    Depth one bounce further (Cycles' PATH_RAY_EMISSION); Ray Length is set per sampled point
    (``sampled_distance``)."""
    r = state.light_path[i]
    _write(regs, 0, r[BOUNCE] + 1, r[DIFFUSE], r[GLOSSY], r[TRANSPARENT], r[TRANSMISSION], 0.0)


@inlined
def sampled_distance(regs, distance):
    """Ray Length of a point light sampling picked on an emitter: its distance from the shading point."""
    regs[regs.shape[0] - FIELDS + RAY_LENGTH] = distance


@inlined
def light_path_output(regs, field):
    """Output ``field`` (an ``OUTPUTS`` index) as the caller wrote it."""
    return regs[regs.shape[0] - FIELDS + field]


def reads_light_path(material_arrays) -> bool:
    """Whether some material program of ``material_arrays`` (``table.MaterialArrays``) reads the node."""
    from . import opcodes as op

    instructions = material_arrays.programs.instructions
    return bool(len(instructions) and (instructions[:, op.OP] == op.LIGHT_PATH).any())
