"""Lights: Blender lights, emissive meshes and the world, behind one interface.

Every light sampled by next-event estimation implements ``sample(p [n,3], u [n,3],
lam [n,K]) -> (wi [n,3] unit, distance [n] (inf: distant), Li [n,K], pdf [n])``
(pdf in solid angle; 1 for delta lights) and has ``delta``. Lights rays can hit
also have ``intersect(o, d) -> t`` (``hittable``), ``emitted(o, d, t, lam)`` and
``pdf(o, d, t)``; a sun with an angle is hit by escaping rays (``distant``).
"""

from __future__ import annotations

import numpy as np

from ..bsdf.emission import emission_spectrum_of, is_emissive
from ..errors import PrismInputError
from .area import AreaLight
from .mesh import MeshEmitters
from .point import PointLight
from .sun import SunLight
from .world import WorldLight

__all__ = ["LightSet", "AreaLight", "MeshEmitters", "PointLight", "SunLight", "WorldLight"]


def _make(light, spectra):
    spectrum = spectra.emission(light.spectrum)
    if light.kind == "point":
        return PointLight(light, spectrum)
    if light.kind == "spot":
        return PointLight(light, spectrum, spot=True)
    if light.kind == "area":
        if light.area_shape not in ("rectangle", "disk"):
            raise PrismInputError(
                f"Light '{light.name}': area shape '{light.area_shape}' is not supported; use Rectangle or Disk."
            )
        return AreaLight(light, spectrum)
    if light.kind == "sun":
        return SunLight(light, spectrum)
    raise PrismInputError(f"Light '{light.name}': unknown light type '{light.kind}'.")


def _emits(light) -> bool:
    if light.kind == "sun":
        return light.irradiance_w_m2 > 0
    if light.kind == "area" and not (light.size_u_m > 0 and light.size_v_m > 0):
        return False
    return light.power_w > 0


class LightSet:
    """All emitters of a scene. NEE picks one of ``lights`` with probability
    ``select_prob`` proportional to its estimated power (spectra are luminance-normalised,
    so powers compare): P for point, spot and area lights, E pi R^2 for a sun (R: radius
    of the scene's bounding sphere), pi sum(area x strength) for emissive meshes; every
    light keeps at least 1/(20 n) so none is starved."""

    def __init__(self, scene, spectra, use_mesh_lights=True):
        self.lights = [_make(light, spectra) for light in scene.lights if _emits(light)]
        self.mesh = None
        emissive = [i for i, m in enumerate(scene.materials) if is_emissive(m)]
        if use_mesh_lights and emissive and len(scene.triangles):
            tri_mat = np.asarray(scene.triangle_material)
            tris = np.flatnonzero(np.isin(tri_mat, emissive))
            corners = np.asarray(scene.vertices, dtype=np.float64)[np.asarray(scene.triangles)[tris]]
            area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
            tris = tris[np.isfinite(area) & (area > 0)]
            if len(tris):
                spec_of_mat = {m: k for k, m in enumerate(emissive)}
                mats = tri_mat[tris]
                spectra_list = [emission_spectrum_of(scene.materials[m], spectra) for m in emissive]
                self.mesh = MeshEmitters(
                    scene.vertices,
                    scene.triangles,
                    tris,
                    np.array([scene.materials[m].emission_strength for m in mats]),
                    np.array([spec_of_mat[m] for m in mats]),
                    spectra_list,
                    len(scene.triangles),
                )
                self.lights.append(self.mesh)
        self.mesh_index = len(self.lights) - 1 if self.mesh is not None else -1
        self.hittable = [(i, light) for i, light in enumerate(self.lights) if getattr(light, "hittable", False)]
        self.distant = [(i, light) for i, light in enumerate(self.lights) if getattr(light, "distant", False)]
        self.world = WorldLight(scene.world, spectra.world_emission(scene.world.color))
        self.select_prob = _selection(self.lights, scene)
        self.select_cdf = np.cumsum(self.select_prob)

    def __len__(self):
        return len(self.lights)


def _selection(lights, scene):
    if not lights:
        return np.zeros(0)
    verts = np.asarray(scene.vertices, dtype=np.float64)
    radius = 0.5 * float(np.linalg.norm(np.ptp(verts, axis=0))) if len(verts) else 1.0
    power = []
    for light in lights:
        if isinstance(light, SunLight):
            power.append(light.irradiance * np.pi * max(radius, 1e-3) ** 2)
        elif isinstance(light, MeshEmitters):
            power.append(np.pi * light.total)
        elif isinstance(light, AreaLight):
            power.append(light.radiance * np.pi * light.area)
        else:
            power.append(light.intensity * 4.0 * np.pi)
    power = np.maximum(np.nan_to_num(np.asarray(power, dtype=np.float64)), 0.0)
    n = len(lights)
    prob = power / power.sum() if power.sum() > 0 else np.full(n, 1.0 / n)
    prob = np.maximum(prob, 1.0 / (20 * n))
    return prob / prob.sum()

