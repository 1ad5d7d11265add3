"""``scene.Light`` list + emissive materials + world → ``LightArrays``, with selection probabilities.

Light sampling picks one light with probability ∝ its power (spectra are luminance-normalised, so
powers compare): P for point, spot and area lights, E π R² for a sun (R: the scene's bounding-sphere
radius), π Σ area × strength for the emissive meshes, π R² ∫ L dω for the world's background; every
light keeps at least 1/(20 n) so none starves. The background (``lights.environment``) is one light
(``environment_index``, -1 when it is black, a constant colour, or its sampling is off: then escaping
rays alone find it); a sky's Sun disc is a distant light of its own.
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass

import numpy as np

from ..errors import PrismInputError
from ..light_linking import link_tables
from .area import area_power, area_row
from .environment import build_environment
from .mesh import build_mesh_emitters
from .point import point_power, point_row
from .row import (DISK, ENVIRONMENT, KIND_NAMES, L_CAMERA, L_KIND, LIGHT_ROW, MESH, POINT, RECTANGLE, SPHERE, SUN,
                  SUN_DISK)
from .sun import sun_power, sun_row

#: ``environment`` (``lights.environment.EnvironmentArrays``) and ``environment_index`` (its row, -1:
#: not light-sampled); ``camera_environment`` the background camera rays see (``World.camera_background``, a
#: backplate; else ``environment`` itself) and ``backplate`` whether it differs; ``group`` int32 [rows] and
#: ``world_group``: light group index of each light and of the world (-1: none); ``links`` the
#: ``light_linking.LinkTables`` (empty without light or shadow linking); ``catcher_excluded`` uint8 [rows +
#: triangles] (emitters numbered as ``light_linking.emitter_sets`` numbers them): 1 for a light whose object is
#: not a shadow catcher (Object ▸ Visibility ▸ Shadow Catcher of a light, on by default) and an emissive
#: triangle of an object that is not one: Cycles' SHADER_EXCLUDE_SHADOW_CATCHER, they do not light the shadow
#: catcher's pass (``stages.shadow_catcher``); [1] of 0 in scenes without a catcher.
LightArrays = namedtuple(
    "LightArrays", "rows select_prob select_cdf hittable mesh mesh_index environment environment_index group "
    "world_group links camera_environment backplate catcher_excluded"
)


@dataclass
class LightTable:
    arrays: LightArrays
    names: list  # one per row
    kinds: list  # Blender kinds ("point", "area", "sun", "emissive meshes", "world") per row
    power: np.ndarray | None = None  # per row, the selection's power (luminance-normalised watts)
    scene_radius_m: float = 1.0
    world: str = ""  # what the background is, for the render stats ("" when black)
    world_emission: tuple | None = None  # (spectrum id, power) of the background, for the wavelength guide


def _emits(light) -> bool:
    if light.kind == "sun":
        return light.irradiance_w_m2 > 0
    if light.kind == "area" and not (light.size_u_m > 0 and light.size_v_m > 0):
        return False
    return light.power_w > 0


def _light_row(light, spectra, offset):
    try:
        spectrum = spectra.emission(light.spectrum)
    except PrismInputError as error:
        raise PrismInputError(f"Light '{light.name}': {error}") from None
    if light.kind in ("point", "spot"):
        return point_row(light, spectrum, offset)
    if light.kind == "area":
        if light.area_shape not in ("rectangle", "disk"):
            raise PrismInputError(
                f"Light '{light.name}': area shape '{light.area_shape}' is not supported; use Rectangle or Disk."
            )
        return area_row(light, spectrum, offset)
    if light.kind == "sun":
        return sun_row(light, spectrum)
    raise PrismInputError(f"Light '{light.name}': unknown light type '{light.kind}'.")


def _power(row, scene_radius_m, mesh_total, environment_total):
    kind = int(row[L_KIND])
    if kind == ENVIRONMENT:
        return np.pi * max(scene_radius_m, 1e-3) ** 2 * environment_total
    if kind in (POINT, SPHERE):
        return point_power(row)
    if kind in (RECTANGLE, DISK):
        return area_power(row)
    if kind in (SUN, SUN_DISK):
        return sun_power(row, scene_radius_m)
    return np.pi * mesh_total


def build_lights(scene, spectra, vertices, triangles, triangle_material, emission_strength, offset,
                 use_mesh_lights=True, light_groups=(), triangle_group=None, triangle_objects=None,
                 triangle_catcher=None) -> LightTable:
    """Rows for the scene's lights; ``vertices``/``triangles``/``triangle_material`` are the render's
    camera-relative geometry, ``emission_strength`` [M] the materials' (0 = not emissive), ``offset``
    the camera position subtracted from every position. ``light_groups``: the names of the light groups
    with a pass (lights of another group count in none); ``triangle_group`` [T] the group index of each
    triangle's object (None: none). ``triangle_objects`` [T]: the object of each triangle, for
    ``scene.light_links`` (None: no linking). ``triangle_catcher`` bool [T]: whether each triangle's object
    is a shadow catcher (None: the scene has none)."""
    group_index = {name: g for g, name in enumerate(light_groups)}
    rows, names, kinds, groups, blender_lights, excluded = [], [], [], [], [], []
    for light in scene.lights:
        if _emits(light):
            excluded.append(not getattr(light, "shadow_catcher", True))
            rows.append(_light_row(light, spectra, offset))
            names.append(light.name)
            blender_lights.append(light.name)
            kinds.append(light.kind)
            groups.append(group_index.get(light.light_group, -1))
    strength = np.asarray(emission_strength, np.float64) if use_mesh_lights else np.zeros(len(emission_strength))
    mesh, mesh_total = build_mesh_emitters(vertices, triangles, triangle_material, strength, triangle_group)
    mesh_index = -1
    if mesh_total > 0:
        row = np.zeros(LIGHT_ROW)
        row[L_KIND] = MESH
        mesh_index = len(rows)
        rows.append(row)
        names.append(KIND_NAMES[MESH])
        kinds.append(KIND_NAMES[MESH])
        groups.append(-1)
    world = scene.world
    world_group = group_index.get(getattr(world, "light_group", ""), -1) if world is not None else -1
    environment, environment_total, sky_rows, guide_spectrum = build_environment(world, spectra)
    backplate = getattr(world, "camera_background", None)
    camera_environment = build_environment(backplate, spectra).arrays if backplate is not None else environment
    for row in sky_rows:
        if backplate is not None:
            row[L_CAMERA] = 0.0  # camera rays see the backplate, not the lighting sky's sun
        rows.append(row)
        names.append(f"{world.name} sun")
        kinds.append("sun")
        groups.append(world_group)
    environment_index = -1
    if environment_total > 0 and world.sampled:
        row = np.zeros(LIGHT_ROW)
        row[L_KIND] = ENVIRONMENT
        environment_index = len(rows)
        rows.append(row)
        names.append(world.name)
        kinds.append(KIND_NAMES[ENVIRONMENT])
        groups.append(world_group)
    verts = np.asarray(vertices, np.float64)
    radius = 0.5 * float(np.linalg.norm(np.ptp(verts, axis=0))) if len(verts) else 1.0
    power = np.array([_power(r, radius, mesh_total, environment_total) for r in rows], dtype=np.float64)
    power = np.maximum(np.nan_to_num(power), 0.0)
    n = len(rows)
    if n:
        prob = power / power.sum() if power.sum() > 0 else np.full(n, 1.0 / n)
        prob = np.maximum(prob, 1.0 / (20 * n))
        prob /= prob.sum()
    else:
        prob = np.zeros(0)
    cdf = np.cumsum(prob)
    if n:
        cdf[-1] = 1.0
    table = np.array(rows, dtype=np.float64).reshape(-1, LIGHT_ROW)
    hittable = np.array([i for i, r in enumerate(rows) if int(r[L_KIND]) in (SPHERE, RECTANGLE, DISK)], np.int32)
    arrays = LightArrays(table if n else np.zeros((1, LIGHT_ROW)), prob, cdf, hittable, mesh, mesh_index,
                         environment, environment_index, np.array(groups if n else [-1], np.int32), world_group,
                         link_tables(getattr(scene, "light_links", None), triangle_objects,
                                     blender_lights + [None] * (n - len(blender_lights))),
                         camera_environment, backplate is not None,
                         _catcher_excluded(excluded, max(n, 1), triangle_catcher))
    return LightTable(arrays, names, kinds, power, radius, _world_description(world, environment_index),
                      _world_emission(world, environment_total, guide_spectrum, radius))


def _catcher_excluded(lights_excluded, rows, triangle_catcher):
    """``LightArrays.catcher_excluded``: Blender lights as their objects say, the emissive meshes' row, the
    world and its suns included (Cycles makes the world a catcher), triangles of non-catcher objects out."""
    if triangle_catcher is None:
        return np.zeros(1, np.uint8)
    out = np.zeros(rows + len(triangle_catcher), np.uint8)
    out[:len(lights_excluded)] = np.asarray(lights_excluded, bool)
    out[rows:] = ~np.asarray(triangle_catcher, bool)
    return out


def _world_emission(world, environment_total, guide_spectrum, radius):
    """(spectrum id, power through the scene's bounding sphere) of the background, or None."""
    if world is None or world.is_black() or guide_spectrum < 0:
        return None
    if world.kind == "constant":
        return guide_spectrum, np.pi * float(world.strength) * np.pi * radius * radius
    return guide_spectrum, np.pi * radius * radius * environment_total


def _world_description(world, environment_index) -> str:
    if world is None or world.is_black():
        return ""
    kind = {"constant": "colour", "image": "HDRI", "sky": "Nishita sky"}.get(world.kind, world.kind)
    if world.kind == "constant":
        return f"world {kind}"
    return f"world {kind}" + (" (light-sampled)" if environment_index >= 0 else " (not light-sampled)")
