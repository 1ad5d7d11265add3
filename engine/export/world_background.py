"""A world's Surface as Cycles sums it: Background nodes under Add Shader and Mix Shader nodes, each with
its weight, strength and colour (a constant, or the Environment or Sky Texture feeding it).

Constants linked in from Value and RGB nodes are folded; a Mix Shader's Fac taken from Light Path ▸ Is
Camera Ray splits what camera rays see from what lights the scene (Cycles' backplate set-up); any other
link into a Background's Strength or Color (or a Mix Shader's Fac) is reported as ignored, with the
socket's own value that is used instead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..properties.node_links import upstream
from ..tracer.errors import PrismInputError

TEXTURES = ("ShaderNodeTexEnvironment", "ShaderNodeTexSky")
#: Shader nodes between the World Output and its Backgrounds Prism follows (a tree, not a chain, is usual).
MAX_SHADER_DEPTH = 64


@dataclass
class BackgroundTerm:
    """One Background node as it adds to the world: ``weight`` (the Mix Shader factors above it) ×
    ``strength`` × (``colour``, or ``texture``'s colour when an Environment or Sky Texture feeds Color)."""

    node: object
    weight: float
    strength: float
    colour: tuple
    texture: object = None


def _own(socket):
    value = socket.default_value
    try:
        return tuple(float(v) for v in value[:3])
    except TypeError:
        return float(value)


def constant_input(world, node, name, warnings):
    """The value of ``node``'s input ``name``: its own, or a Value or RGB node's folded in; any other link is
    ignored (and reported), the socket's own value used."""
    socket = node.inputs[name]
    source, output = upstream(socket)
    if source is None:
        return _own(socket)
    if source.bl_idname in ("ShaderNodeValue", "ShaderNodeRGB"):
        folded = _own(output)
        own = _own(socket)
        if isinstance(own, float) and isinstance(folded, tuple):  # an RGB node into a float: its luminance
            folded = 0.2126 * folded[0] + 0.7152 * folded[1] + 0.0722 * folded[2]
        elif isinstance(own, tuple) and isinstance(folded, float):
            folded = (folded,) * 3
        return folded
    own = _own(socket)
    shown = f"{own:g}" if isinstance(own, float) else "(" + ", ".join(f"{v:g}" for v in own) + ")"
    if warnings is not None:
        warnings.append(f"World '{world.name}': the link from '{source.name}' into {node.bl_label} '{node.name}' "
                        f"{name} is ignored; Prism folds only Value and RGB nodes there and uses the socket's own "
                        f"value {shown}.")
    return own


def background_term(world, node, weight, warnings) -> BackgroundTerm:
    strength = constant_input(world, node, "Strength", warnings)
    source, _ = upstream(node.inputs["Color"])
    if source is not None and source.bl_idname in TEXTURES:
        return BackgroundTerm(node, weight, strength, _own(node.inputs["Color"]), source)
    return BackgroundTerm(node, weight, strength, constant_input(world, node, "Color", warnings))


def is_camera_ray_mix(node) -> bool:
    """Whether ``node`` is a Mix Shader whose Fac is a Light Path node's Is Camera Ray: Cycles' backplate
    set-up, where camera rays see the second shader and every other ray the first."""
    if node.type != "MIX_SHADER":
        return False
    source, output = upstream(node.inputs["Fac"])
    return source is not None and source.type == "LIGHT_PATH" and output.identifier == "Is Camera Ray"


def has_camera_ray_mix(world, surface_socket) -> bool:
    """Whether a Mix Shader under the World Output's Surface picks its shader by Is Camera Ray."""
    def found(socket, depth):
        node, _ = upstream(socket)
        if node is None or depth > MAX_SHADER_DEPTH:
            return False
        if is_camera_ray_mix(node):
            return True
        return node.type in ("ADD_SHADER", "MIX_SHADER") and any(
            found(node.inputs[i], depth + 1) for i in ((0, 1) if node.type == "ADD_SHADER" else (1, 2)))

    return found(surface_socket, 0)


def background_terms(world, surface_socket, warnings, camera_rays: bool = False) -> list[BackgroundTerm]:
    """The Background terms feeding the World Output's Surface ``surface_socket`` (empty when none does), as
    rays other than camera rays see them (``camera_rays``: as camera rays see them; the two differ only
    under a Mix Shader driven by Is Camera Ray, ``is_camera_ray_mix``)."""
    terms: list[BackgroundTerm] = []

    def walk(socket, weight, depth):
        node, _ = upstream(socket)
        if node is None or weight <= 0.0:
            return
        if depth > MAX_SHADER_DEPTH:
            raise PrismInputError(f"World '{world.name}': the Surface is deeper than {MAX_SHADER_DEPTH} shader nodes "
                                  f"at '{node.name}'; Prism follows up to {MAX_SHADER_DEPTH}: simplify it.")
        if node.type == "BACKGROUND":
            terms.append(background_term(world, node, weight, warnings))
        elif node.type == "ADD_SHADER":
            walk(node.inputs[0], weight, depth + 1)
            walk(node.inputs[1], weight, depth + 1)
        elif is_camera_ray_mix(node):  # Is Camera Ray is exactly 0 or 1
            walk(node.inputs[2 if camera_rays else 1], weight, depth + 1)
        elif node.type == "MIX_SHADER":
            fac = constant_input(world, node, "Fac", warnings)
            if not math.isfinite(fac):
                raise PrismInputError(f"World '{world.name}': Mix Shader '{node.name}' Fac is {fac:g}; enter a "
                                      "number from 0 to 1.")
            fac = min(max(fac, 0.0), 1.0)
            walk(node.inputs[1], weight * (1.0 - fac), depth + 1)
            walk(node.inputs[2], weight * fac, depth + 1)
        elif warnings is not None:
            warnings.append(f"World '{world.name}': the '{node.name}' node ({node.bl_label}) in the Surface is not "
                            "a Background; Prism renders Background, Add Shader and Mix Shader nodes there and "
                            "leaves it out (black).")

    walk(surface_socket, 1.0, 0)
    return terms
