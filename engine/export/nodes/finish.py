"""The compiled walk → a ``ShaderProgram``: closures whose constant parameters became plain numbers or
spectra, varying ones registers or bindings; the emission; the shading normal; the program itself."""

from __future__ import annotations

from ...tracer.bsdf.closure import (C_ALPHA, C_ETA, C_TINT_SCALE, CONDUCTOR, DIELECTRIC, FRESNEL_DIELECTRIC,
                                    SUBSURFACE, TRANSPARENT)
from ...tracer.materials.shader import ClosureSpec, Colour, HairInputs, ShaderProgram
from .aov_outputs import aov_results
from .normals import bump_map_correction
from .vectors import displacement_bump, displacement_method, true_displacement

_LUMINANCE = (0.2126729, 0.7151522, 0.0721750)


def _colour(c, value):
    """A ``Colour`` for a Value (constant or register) or a measured-metal key."""
    if value is None:
        return None
    if isinstance(value, tuple):
        return Colour(spectrum=value)
    known = c.known(value)
    if known is not None:
        return Colour(rgb=tuple(max(x, 0.0) for x in known))
    return Colour(register=value.register)


def _selection(kind, fresnel, rgb):
    weight = sum(w * x for w, x in zip(_LUMINANCE, rgb))
    if kind == CONDUCTOR and fresnel == FRESNEL_DIELECTRIC:
        weight *= 0.1
    return max(weight, 0.0)


def _closure(c, pending):
    spec = ClosureSpec(pending.kind, fresnel=pending.fresnel, glass=pending.glass, coat_nm=pending.coat_nm,
                       coat_ior=pending.coat_ior, layer=pending.weight.layer)
    scale, colour = c.known(pending.weight.scale), c.known(pending.weight.colour)
    if pending.measured is not None and pending.kind != CONDUCTOR:
        spec.tint = Colour(spectrum=pending.measured)
        if scale is None:
            spec.bindings.append((C_TINT_SCALE, pending.weight.scale.register, True))
        elif scale <= 0.0:
            return None
        else:
            spec.scale = float(scale)
        if colour is None or colour != (1.0, 1.0, 1.0):
            c.warn(pending.node, "has a measured base colour under a coloured layer (coat tint); Prism leaves the "
                                 "layer's tint out there.")
    elif scale is not None and colour is not None:
        rgb = tuple(max(x * scale, 0.0) for x in colour)
        if max(rgb) <= 0.0:
            return None
        spec.tint = Colour(rgb=rgb)
        spec.selection = _selection(pending.kind, pending.fresnel, rgb)
    elif colour is not None:
        spec.tint = Colour(rgb=tuple(max(x, 0.0) for x in colour))
        spec.bindings.append((C_TINT_SCALE, pending.weight.scale.register, True))
    else:
        tinted = pending.weight.colour if scale == 1.0 else c.multiply(pending.weight.colour, pending.weight.scale)
        spec.tint = Colour(register=tinted.register)
    # A measured reflectance replaces the base colour once: in the tint of a diffuse closure (above), in the
    # normal-incidence reflectance s0 of a metal (a diffuse closure's s0 is a second albedo factor); a subsurface
    # closure's tint and its walk's albedo are both the base colour, so it takes both.
    takes_s0 = pending.measured is not None and pending.kind in (CONDUCTOR, SUBSURFACE)  # a walk's albedo, too
    spec.s0 = Colour(spectrum=pending.measured) if takes_s0 else _colour(c, pending.s0)
    spec.s1 = _colour(c, pending.s1)
    spec.multiscatter = pending.multiscatter
    spec.subsurface = pending.subsurface
    spec.multiscatter_colour = _colour(c, pending.multiscatter_colour)
    if pending.alpha is not None:
        alpha = c.known(pending.alpha)
        if alpha is None:
            spec.alpha = 1.0
            spec.bindings.append((C_ALPHA, pending.alpha.register, False))
        else:
            spec.alpha = float(alpha)
    if pending.hair is not None:
        spec.hair = _hair_inputs(c, spec, pending.hair)
    if pending.eta is not None:
        eta = c.known(pending.eta)
        if eta is not None:
            spec.eta = float(eta)
        elif pending.kind == DIELECTRIC:
            c.warn(pending.node, "has a varying IOR; Prism's glass takes a constant index (1.5) there.")
            spec.eta = 1.5
        else:
            spec.bindings.append((C_ETA, pending.eta.register, False))
    return spec


def _hair_inputs(c, spec, hair):
    """A fibre's ``HairInputs``: constant inputs as numbers, varying ones bound to their columns."""
    mode, model, inputs, strand_random, tangent = hair
    values = {"sigma_mode": mode, "model": model, "strand_random": strand_random}
    if tangent is not None and c.known(tangent) is None:  # a constant Tangent: Cycles folds the link away
        values["tangent"] = tangent.register
    for column, (name, value) in inputs.items():
        known = c.known(value)
        if known is None:
            spec.bindings.append((column, value.register, False))
        else:
            values[name] = float(known)
    spec.alpha = 1.0  # no microfacet roughness: a fibre is never a mirror (``SMOOTH_ALPHA``)
    return HairInputs(**values)


def _closure_normals(c, default_normal):
    """The material's shading normal (a Value, or None for the surface's) and, per pending closure, the
    register of a normal of its own or -1. Like Cycles, every closure shades with its own normal (a Coat
    Normal, shaders with different Normal inputs); the material's frame takes the normal most closures
    share (the first on a tie), and only the others carry theirs."""
    normals = [p.normal if p.normal is not None else default_normal for p in c.closures]
    keys = [n.register if n is not None else -1 for n in normals]
    voters = [key for key, p in zip(keys, c.closures) if p.kind != TRANSPARENT]  # straight through: no normal
    if not voters:
        return default_normal, [-1] * len(keys)
    shared = max(voters, key=lambda key: (voters.count(key), -voters.index(key)))
    surface = None
    own = []
    for n, key, pending in zip(normals, keys, c.closures):
        if key == shared or pending.kind == TRANSPARENT:
            own.append(-1)
            continue
        if n is None:  # the surface's own normal, while the material's frame takes another one
            surface = surface if surface is not None else c.normal()
            n = surface
        own.append(n.register)
    return normals[keys.index(shared)], own


def _emission(c, program):
    terms = c.emission
    if not terms:
        return
    if len(terms) == 1 and terms[0].spectrum is not None:
        term = terms[0]
        program.emission = Colour(spectrum=term.spectrum)
        strength = c.known(term.scale)
        if strength is None:
            program.emission_strength, program.emission_scale = 1.0, term.scale.register
        else:
            program.emission_strength = float(strength)
        return
    total = None
    for term in terms:
        colour = term.colour if term.colour is not None else c.const(1.0, 1.0, 1.0)
        part = c.multiply(colour, term.scale)
        total = part if total is None else c.vector_math("ADD", total, part)
    known = c.known(total)
    if known is not None:
        if max(known) <= 0.0:
            return
        largest = max(known)
        program.emission = Colour(rgb=tuple(x / largest for x in known))
        program.emission_strength = float(largest)
    else:
        program.emission = Colour(register=total.register)
        program.emission_strength = 1.0


def _read_registers(program) -> set[int]:
    """Registers the tracer reads after the program ran: closure colours and bindings, normal, emission."""
    live = set()
    for spec in program.closures:
        for colour in (spec.tint, spec.s0, spec.s1):
            if colour is not None and colour.register is not None:
                live.update(range(colour.register, colour.register + 3))
        live.update(register for _, register, _ in spec.bindings)
        if spec.normal >= 0:
            live.update(range(spec.normal, spec.normal + 3))
        if spec.hair is not None and spec.hair.tangent >= 0:
            live.update(range(spec.hair.tangent, spec.hair.tangent + 3))
    if program.normal >= 0:
        live.update(range(program.normal, program.normal + 3))
    if program.emission is not None and program.emission.register is not None:
        live.update(range(program.emission.register, program.emission.register + 3))
    if program.emission_scale >= 0:
        live.add(program.emission_scale)
    if program.displacement >= 0:
        live.update(range(program.displacement, program.displacement + 3))
    for register in (program.volume_density, program.volume_emission):
        if register >= 0:
            live.add(register)
    for registers in program.aov_registers.values():  # read at the first hit (the AOV passes)
        for name, register in registers.items():
            live.update(range(register, register + (3 if name == "Color" else 1)))
    return live


def finish(c) -> ShaderProgram:
    """The ``ShaderProgram`` of compiler ``c`` after its walk."""
    method = displacement_method(c.material)
    socket = getattr(c, "displacement", None)
    # "Both": the vertices move and the same displacement bends the normal between them, as Cycles'
    # bump_from_displacement (which Cycles computes in object space: see docs/displacement.md)
    default_normal = displacement_bump(c, socket) if socket is not None and method in ("BUMP", "BOTH") else None
    moved = true_displacement(c, socket) if socket is not None and method != "BUMP" else None
    normal, own_normals = _closure_normals(c, default_normal)
    closures = []
    for pending, own in zip(c.closures, own_normals):
        spec = _closure(c, pending)
        if spec is not None:
            spec.normal = own
            closures.append(spec)
    program = ShaderProgram(closures)
    _emission(c, program)
    program.normal = normal.register if normal is not None else -1
    program.displacement = moved.register if moved is not None else -1
    program.volume_density = c.volume_density.register if c.volume_density is not None else -1
    program.volume_emission = c.volume_emission.register if c.volume_emission is not None else -1
    program.bump_map_correction = bump_map_correction(c)
    program.surface_missing = getattr(c, "surface_missing", False)
    program.aov_registers, program.aov_constants = aov_results(c, c.aov_outputs)
    program.instructions = c.builder.instructions(live=_read_registers(program))
    program.constants = c.builder.initial_registers()
    program.register_count = c.builder.register_count
    program.images = list(c.images)
    if (not program.has_program and not any(spec.bindings for spec in closures) and program.normal < 0
            and program.displacement < 0 and max(program.volume_density, program.volume_emission) < 0):
        program.constants = program.constants[:0]
        program.register_count = 0
    return program

