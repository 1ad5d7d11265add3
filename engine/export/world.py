"""The scene's world → ``tracer.scene.World``: its Background's colour (a constant, an Environment
Texture or a Nishita Sky Texture, with Mapping) and strength, and whether Cycles' settings ask for the
world to be light-sampled (World ▸ Settings ▸ Sampling: None turns it off)."""

from __future__ import annotations

import math

from ..tracer.errors import PrismInputError
from ..tracer.scene import Sky, World
from .environment_image import image_rgb
from .world_mapping import linked_source, texture_matrix

_INTERPOLATION = {"Linear": "linear", "Closest": "closest"}


def _background_node(world):
    tree = world.node_tree if world.use_nodes else None
    if tree is None:
        return None
    output = tree.get_output_node("ALL")
    if output is not None and output.inputs["Surface"].is_linked:
        node, _ = linked_source(output.inputs["Surface"])
        if node is not None and node.type == "BACKGROUND":
            return node
    return next((node for node in tree.nodes if node.type == "BACKGROUND"), None)


def _check(world, color, strength):
    if not (all(math.isfinite(c) and c >= 0 for c in color) and math.isfinite(strength) and strength >= 0):
        raise PrismInputError(f"World '{world.name}': background colour and strength must be finite and not negative.")


def _environment(world, node, exported: World, warnings) -> None:
    where = f"World '{world.name}', Environment Texture '{node.name}'"
    if node.image is None:
        raise PrismInputError(f"{where} has no image: open an image in it or unlink it from the Background.")
    if node.projection != "EQUIRECTANGULAR":
        raise PrismInputError(f"{where}: projection {node.projection.replace('_', ' ').title()} is not supported; "
                              "set it to Equirectangular.")
    exported.interpolation = _INTERPOLATION.get(node.interpolation, "linear")
    if node.interpolation not in _INTERPOLATION and warnings is not None:
        warnings.append(f"{where}: {node.interpolation} interpolation is rendered as Linear.")
    exported.kind = "image"
    exported.image_rgb = image_rgb(node.image, where, warnings)
    exported.to_texture = texture_matrix(node.inputs["Vector"], where, warnings)


def _sky(world, node, exported: World, warnings) -> None:
    where = f"World '{world.name}', Sky Texture '{node.name}'"
    if node.sky_type != "NISHITA":
        raise PrismInputError(f"{where}: sky type {node.sky_type.replace('_', ' ').title()} is not supported; "
                              "set Sky Type to Nishita (Prism evaluates it per wavelength).")
    exported.kind = "sky"
    exported.sky = Sky(
        sun_elevation_rad=float(node.sun_elevation), sun_rotation_rad=float(node.sun_rotation),
        sun_disc=bool(node.sun_disc), sun_size_rad=float(node.sun_size), sun_intensity=float(node.sun_intensity),
        altitude_m=float(node.altitude), air_density=float(node.air_density),
        dust_density=float(node.dust_density), ozone_density=float(node.ozone_density),
    )
    vector = node.inputs.get("Vector")
    if vector is not None:
        exported.to_texture = texture_matrix(vector, where, warnings)


def export_world(scene, warnings: list[str] | None = None, view_layer=None) -> World:
    """The background of ``scene.world`` (a black one when there is no world, or when ``view_layer``'s
    Filter ▸ Environment is off: Cycles then neither shows nor samples the world, it lights nothing)."""
    world = scene.world
    if world is None:
        return World(color=(0.0, 0.0, 0.0), strength=0.0)
    if view_layer is not None and not view_layer.use_sky:
        return World(color=(0.0, 0.0, 0.0), strength=0.0, name=world.name)
    cycles = getattr(world, "cycles", None)
    sampled = getattr(cycles, "sampling_method", "AUTOMATIC") != "NONE"
    node = _background_node(world)
    if node is None:
        color = tuple(float(c) for c in world.color)
        _check(world, color, 1.0)
        return World(color=color, strength=1.0, sampled=sampled, name=world.name)
    if node.inputs["Strength"].is_linked and warnings is not None:
        warnings.append(f"World '{world.name}': the link into Background 'Strength' is ignored; "
                        "Prism uses the socket's own value.")
    color = tuple(float(c) for c in node.inputs["Color"].default_value[:3])
    strength = float(node.inputs["Strength"].default_value)
    _check(world, color, strength)
    exported = World(color=color, strength=strength, sampled=sampled, name=world.name)
    source, _ = linked_source(node.inputs["Color"])
    if source is None:
        return exported
    if source.bl_idname == "ShaderNodeTexEnvironment":
        _environment(world, source, exported, warnings)
    elif source.bl_idname == "ShaderNodeTexSky":
        _sky(world, source, exported, warnings)
    elif warnings is not None:
        warnings.append(f"World '{world.name}': the link from '{source.name}' into Background 'Color' is ignored; "
                        "Prism renders a colour, an Environment Texture or a Sky Texture there (the socket's own "
                        "colour is used).")
    return exported
