"""The scene's world → ``tracer.scene.World``: its Backgrounds (``world_background``: summed under Add
Shader and Mix Shader, as Cycles sums them) with their colour (a constant, an Environment Texture or a
Nishita Sky Texture, with Mapping) and strength, and whether Cycles' settings ask for the world to be
light-sampled (World ▸ Settings ▸ Sampling: None turns it off).

Prism's world is one textured or constant radiance: constant Backgrounds add up to one colour, and a
constant added to an Environment Texture is added to its texels; a Sky Texture summed with anything
else, or two textures, are refused with the fix."""

from __future__ import annotations

import math

from ..tracer.errors import PrismInputError
from ..tracer.scene import Sky, World
from ..properties.node_links import is_linked
from .animated import settings_source
from .environment_image import image_rgb, replace_bad_texels
from .float_range import check_light_value
from .world_background import BackgroundTerm, background_term, background_terms, has_camera_ray_mix
from .world_mapping import texture_matrix
from .world_volume import export_world_volume

_INTERPOLATION = {"Linear": "linear", "Closest": "closest"}


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
    exported.image_rgb = replace_bad_texels(image_rgb(node.image, where, warnings), where, node.image.name, warnings)
    if exported.image_rgb.size:
        check_light_value(float(exported.image_rgb.max()) * exported.strength, where,
                          f"the brightest texel of image '{node.image.name}' × the Background's Strength")
    exported.to_texture = texture_matrix(node.inputs["Vector"], where, warnings)


_SKY_SETTINGS = (("sun_elevation", "Sun Elevation"), ("sun_rotation", "Sun Rotation"), ("sun_size", "Sun Size"),
                 ("sun_intensity", "Sun Intensity"), ("altitude", "Altitude"), ("air_density", "Air"),
                 ("dust_density", "Dust"), ("ozone_density", "Ozone"))


def _check_sky(where, node) -> None:
    """A NaN or infinite sky setting (set from Python: Blender's fields clamp numbers, not NaN) renders
    black silently: refuse it."""
    for attribute, label in _SKY_SETTINGS:
        value = float(getattr(node, attribute))
        if not math.isfinite(value):
            raise PrismInputError(f"{where}: {label} is {value:g}; enter a finite number (Sky Texture ▸ {label}).")


def _sky(world, node, exported: World, warnings) -> None:
    where = f"World '{world.name}', Sky Texture '{node.name}'"
    if node.sky_type != "NISHITA":
        raise PrismInputError(f"{where}: sky type {node.sky_type.replace('_', ' ').title()} is not supported; "
                              "set Sky Type to Nishita (Prism evaluates it per wavelength).")
    _check_sky(where, node)
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


def _surface_terms(world, tree, warnings, camera_rays: bool = False) -> list[BackgroundTerm]:
    """The Backgrounds of the active World Output's Surface (as camera rays see them with ``camera_rays``);
    with nothing linked there (or no World Output), the tree's first Background node, as Prism has always
    read such worlds."""
    output = tree.get_output_node("ALL")
    if output is not None and is_linked(output.inputs["Surface"]):
        return background_terms(world, output.inputs["Surface"], warnings, camera_rays)
    node = next((n for n in tree.nodes if n.type == "BACKGROUND"), None)
    return [] if node is None else [background_term(world, node, 1.0, warnings)]


def _constant_sum(world, terms) -> tuple[float, float, float]:
    total = [0.0, 0.0, 0.0]
    for term in terms:
        _check(world, term.colour, term.strength)
        for k in range(3):
            total[k] += term.weight * term.strength * term.colour[k]
    return tuple(total)


def _textured_world(world, term, constant, exported: World, warnings) -> World:
    """``exported`` (carrying ``term``'s strength) textured by ``term``'s Environment or Sky Texture, plus
    the ``constant`` radiance of the other Backgrounds."""
    _check(world, term.colour, term.strength)
    if term.texture.bl_idname == "ShaderNodeTexEnvironment":
        _environment(world, term.texture, exported, warnings)
    else:
        check_light_value(exported.strength, f"World '{world.name}', Background '{term.node.name}'", "Strength")
        _sky(world, term.texture, exported, warnings)
    if not max(constant) > 0:
        return exported
    if exported.kind == "sky":
        raise PrismInputError(f"World '{world.name}': a Sky Texture is summed with another Background (Add or Mix "
                              "Shader); Prism renders a Sky Texture only on its own: remove the other Background.")
    if not exported.strength > 0:
        return World(color=constant, strength=1.0, sampled=exported.sampled, name=world.name)
    # Σ = strength × texel + constant = strength × (texel + constant / strength): exact, texel by texel
    offset = [c / exported.strength for c in constant]
    exported.image_rgb = (exported.image_rgb + offset).astype(exported.image_rgb.dtype)
    return exported


def export_world(scene, warnings: list[str] | None = None, view_layer=None) -> World:
    """The background of ``scene.world`` (a black one when there is no world, or when ``view_layer``'s
    Filter ▸ Environment is off: Cycles then neither shows nor samples the world, it lights nothing). A world
    whose Surface picks a shader by Light Path ▸ Is Camera Ray (a backplate) carries what camera rays see
    as its ``camera_background``."""
    world = scene.world
    if world is None:
        return World(color=(0.0, 0.0, 0.0), strength=0.0)
    world = settings_source(world)  # the evaluated copy where animated: ``animated``
    if view_layer is not None and not view_layer.use_sky:
        return World(color=(0.0, 0.0, 0.0), strength=0.0, name=world.name)
    tree = world.node_tree if world.use_nodes else None
    exported = _world_as_seen(world, tree, warnings, camera_rays=False)
    exported.medium = export_world_volume(world, tree, warnings)
    output = tree.get_output_node("ALL") if tree is not None else None
    if output is not None and has_camera_ray_mix(world, output.inputs["Surface"]):
        seen_warnings: list[str] = []  # the backplate's own; what both sides share is told once
        exported.camera_background = _world_as_seen(world, tree, seen_warnings, camera_rays=True)
        if warnings is not None:
            warnings.extend(w for w in dict.fromkeys(seen_warnings) if w not in warnings)
        if exported.camera_background.kind == "sky":
            raise PrismInputError(f"World '{world.name}': camera rays see a Sky Texture through Light Path ▸ Is "
                                  "Camera Ray; Prism shows a constant colour or an Environment Texture there: "
                                  "light with the Sky and show an image, or use the Sky for both.")
    return exported


def _world_as_seen(world, tree, warnings, camera_rays: bool) -> World:
    """The world's background as rays other than camera rays see it, or as camera rays do."""
    cycles = getattr(world, "cycles", None)
    sampled = getattr(cycles, "sampling_method", "AUTOMATIC") != "NONE"
    terms = _surface_terms(world, tree, warnings, camera_rays) if tree is not None else None
    if terms is None or (not terms and not any(n.type == "BACKGROUND" for n in tree.nodes)):
        color = tuple(float(c) for c in world.color)
        _check(world, color, 1.0)
        check_light_value(max(color), f"World '{world.name}'", "Color")
        return World(color=color, strength=1.0, sampled=sampled, name=world.name)
    textured = [t for t in terms if t.texture is not None]
    constant = _constant_sum(world, [t for t in terms if t.texture is None])
    if len(textured) > 1:
        names = " and ".join(f"'{t.node.name}'" for t in textured[:2])
        raise PrismInputError(f"World '{world.name}': Backgrounds {names} both show a texture; Prism renders one "
                              "textured Background (plus constant ones): bake them into one image.")
    if textured:
        term = textured[0]
        exported = World(color=term.colour, strength=term.weight * term.strength, sampled=sampled, name=world.name)
        return _textured_world(world, term, constant, exported, warnings)
    if len(terms) == 1 and terms[0].weight == 1.0:  # one Background: its own colour and strength
        color, strength = terms[0].colour, terms[0].strength
    else:
        color, strength = constant, 1.0
    check_light_value(max(color) * strength, f"World '{world.name}'", "Background Color × Strength")
    return World(color=color, strength=strength, sampled=sampled, name=world.name)
