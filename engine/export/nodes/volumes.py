"""The Material Output's Volume socket → a ``tracer.media.spec.MediumSpec``.

Volume Absorption, Volume Scatter and Principled Volume, alone or summed by Add Shader and Mix Shader (of
constant Fac), with Cycles' meanings (``tracer/media/spec.py``); Volume Scatter's phase functions as Cycles
4.5's (``tracer/media/phase_functions.py``), several lobes as their scattering-weighted mixture. A Density,
or a Principled Volume's Emission Strength, driven by nodes that vary from point to point is baked onto a grid
at render time (``volume_density``); any other input driven by something that varies (a texture, an
attribute) is rendered at the value the socket holds under its link, and the warning says so, naming the
material, node and input. What Prism does not model
(other shaders on the Volume socket) is named in a warning too.
"""

from __future__ import annotations

from ...tracer.media.phase_functions import DRAINE, FOURNIER_FORAND, HENYEY_GREENSTEIN, MIE, RAYLEIGH
from ...tracer.media.spec import MediumSpec
from ...tracer.media.temperature_emission import blackbody_intensity
from . import volume_density
from .graph import follow
from .terms import COLOR, FLOAT


def _constant(c, node, name, context, kind):
    """The input's constant value; a varying one is warned and replaced by the socket's own value."""
    socket = c.socket(node, name)
    source, value_socket = follow(socket, context)
    if source is not None:
        value = c.constant_of(node, name, context, kind)
        if value is not None:
            return value
        own = c.known(c.default_value(value_socket, kind))
        shown = f"{own:g}" if kind == FLOAT else "(" + ", ".join(f"{x:g}" for x in own) + ")"
        c.warn(node, f"has its {name} driven by nodes that vary; Prism renders homogeneous volumes only, so it "
                     f"uses the {name} set on the socket, {shown}, throughout the volume.")
        return own
    return c.known(c.default_value(value_socket, kind))


def _absorption(c, node, context, weight, spec, found):
    colour = _constant(c, node, "Color", context, COLOR)
    density = volume_density.varying_input(c, node, context, weight, found.density)
    spec.absorb.append((density, tuple(colour)))


def _phase_lobe(c, node, context, weight):
    """(weight, kind, parameters) of a Volume Scatter's phase function (``tracer.media.phase_functions``)."""
    phase = getattr(node, "phase", HENYEY_GREENSTEIN)
    inputs = {HENYEY_GREENSTEIN: ("Anisotropy",), FOURNIER_FORAND: ("Backscatter", "IOR"),
              DRAINE: ("Anisotropy", "Alpha"), RAYLEIGH: (), MIE: ("Diameter",)}.get(phase)
    if inputs is None:
        c.warn(node, f"uses the {phase.replace('_', ' ').title()} phase function, which Prism does not know; it "
                     "renders Henyey-Greenstein of the node's Anisotropy.")
        phase, inputs = HENYEY_GREENSTEIN, ("Anisotropy",)
    parameters = tuple(_constant(c, node, name, context, FLOAT) if c.socket(node, name) is not None else 0.0
                       for name in inputs)
    return weight, phase, parameters


def _scatter(c, node, context, weight, spec, lobes, found):
    colour = _constant(c, node, "Color", context, COLOR)
    density = volume_density.varying_input(c, node, context, weight, found.density)
    spec.scatter.append((density, tuple(colour)))
    lobes.append(_phase_lobe(c, node, context, density * max(colour)))


def _principled(c, node, context, weight, spec, lobes, found):
    density = volume_density.varying_input(c, node, context, weight, found.density)
    colour = tuple(_constant(c, node, "Color", context, COLOR))
    absorption = tuple(max(x, 0.0) ** 0.5 for x in _constant(c, node, "Absorption Color", context, COLOR))
    spec.scatter.append((density, colour))
    spec.absorb.append((density, colour, absorption))  # σ_a = density (1 - colour)(1 - sqrt(absorption colour))
    lobes.append((density * max(colour), HENYEY_GREENSTEIN, (_constant(c, node, "Anisotropy", context, FLOAT),)))
    strength = volume_density.varying_input(c, node, context, weight, found.emission, "Emission Strength")
    if node in found.emission.varying:  # radiance per metre per unit of the baked strength
        spec.emission_field.append((strength, tuple(_constant(c, node, "Emission Color", context, COLOR))))
    elif strength > 0.0:
        spec.emission.append((strength, tuple(_constant(c, node, "Emission Color", context, COLOR)), None))
    blackbody = min(max(_constant(c, node, "Blackbody Intensity", context, FLOAT), 0.0), 1.0)
    if blackbody > 0.0:
        _blackbody(c, node, context, weight, blackbody, spec)


def _blackbody(c, node, context, weight, blackbody, spec):
    """Cycles' blackbody emission of a Principled Volume: Stefan-Boltzmann's σ T⁴ (×10⁻⁶ / π), blended from
    1 by the intensity, of the luminance-1 blackbody colour at T, tinted."""
    from ...tracer.spectra.blackbody import MAX_TEMPERATURE_K, MIN_TEMPERATURE_K

    temperature = max(_constant(c, node, "Temperature", context, FLOAT), 0.0)
    tint = tuple(_constant(c, node, "Blackbody Tint", context, COLOR))
    spec.blackbody.append((weight, blackbody, temperature, tint))  # for a Temperature Attribute grid
    intensity = float(blackbody_intensity(temperature, blackbody))
    if not intensity > 1e-5:  # Cycles' cutoff for closures
        return
    shown = min(max(temperature, MIN_TEMPERATURE_K), MAX_TEMPERATURE_K)
    if shown != temperature:
        c.warn(node, f"has a Temperature of {temperature:g} K; Prism's blackbody spectra span "
                     f"{MIN_TEMPERATURE_K:g}-{MAX_TEMPERATURE_K:g} K and colour a temperature outside at the "
                     f"nearer end ({shown:g} K here), at the intensity of the temperature itself (on a Volume "
                     "object with a Temperature Attribute grid, the Temperature times the grid, point by point).")
    spec.emission.append((weight * intensity, tint, shown))


def _walk(c, socket, context, weight, spec, lobes, found):
    source, _ = follow(socket, context)
    if source is None or weight == 0.0:
        return
    node, context = source.node, source.context
    kind = node.bl_idname
    if kind == "ShaderNodeVolumeAbsorption":
        _absorption(c, node, context, weight, spec, found)
    elif kind == "ShaderNodeVolumeScatter":
        _scatter(c, node, context, weight, spec, lobes, found)
    elif kind == "ShaderNodeVolumePrincipled":
        _principled(c, node, context, weight, spec, lobes, found)
    elif kind == "ShaderNodeAddShader":
        _walk(c, node.inputs[0], context, weight, spec, lobes, found)
        _walk(c, node.inputs[1], context, weight, spec, lobes, found)
    elif kind == "ShaderNodeMixShader":
        fac = min(max(_constant(c, node, "Fac", context, FLOAT), 0.0), 1.0)
        _walk(c, node.inputs[1], context, weight * (1.0 - fac), spec, lobes, found)
        _walk(c, node.inputs[2], context, weight * fac, spec, lobes, found)
    else:
        c.warn(node, "is on the Volume socket, where Prism renders Volume Absorption, Volume Scatter and "
                     "Principled Volume only; it is left out (no volume from it).")


def compile_volume(c, socket):
    """The ``MediumSpec`` of the shaders feeding the Volume input ``socket``, or None if they add nothing."""
    spec = MediumSpec(c.material.name)
    lobes, found = [], volume_density.VolumeFields()
    _walk(c, socket, (), 1.0, spec, lobes, found)
    total = sum(w for w, _, _ in lobes)
    if total > 0.0 and any(kind != HENYEY_GREENSTEIN for w, kind, _ in lobes if w > 0.0):
        spec.phase = [lobe for lobe in lobes if lobe[0] > 0.0]  # a tabulated mixture
    elif total > 0.0:
        spec.anisotropy = sum(w * g for w, _, (g,) in lobes) / total
        if len({g for w, _, (g,) in lobes if w > 0.0}) > 1:
            c.warn(c.output_node, f"mixes volume scattering of different Anisotropy; Prism renders one "
                                  f"Henyey-Greenstein lobe of their scattering-weighted mean, {spec.anisotropy:g}.")
    if not (any(d > 0 for d, *_ in spec.scatter + spec.absorb) or spec.emission or spec.emission_field):
        return None
    volume_density.finish_field(c, spec, found.density)
    volume_density.finish_emission(c, spec, found.emission)
    return spec
