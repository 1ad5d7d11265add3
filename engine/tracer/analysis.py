"""Scene analysis: decide before tracing what the scene needs, and say so in one line.

- Hero-wavelength termination only if a used glass disperses or the camera does
  (real lens); otherwise every path carries all its wavelengths to the end.
- Mesh-light sampling only if some used material emits.
- Rough, coated and thin-film code paths only if some used material has them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .bsdf.emission import is_emissive
from .errors import PrismInputError


@dataclass
class SceneAnalysis:
    wavelength_mode: str
    wavelengths_per_path: int
    used_materials: list[int]
    dispersion: bool = False
    dispersive: list[str] = field(default_factory=list)
    camera_disperses: bool = False
    mesh_lights: bool = False
    light_kinds: list[str] = field(default_factory=list)
    features: list[str] = field(default_factory=list)
    world: bool = False
    guided_lines: int = 0
    camera_strategy: str = ""
    see_through_films: bool = False

    def strategy(self, use_mis: bool, pixel_filter: str) -> str:
        """One line for the render stats."""
        parts = [f"{self.wavelength_mode} x{self.wavelengths_per_path}"]
        if self.guided_lines:
            parts[0] += f" guided by {self.guided_lines} emission line(s)"
        if self.dispersion:
            what = ", ".join(self.dispersive + (["lens"] if self.camera_disperses else []))
            parts.append(f"hero-wavelength termination ({what})")
        else:
            parts.append("no dispersion: all wavelengths kept")
        lights = ", ".join(sorted(set(self.light_kinds))) or "none"
        parts.append(f"lights: {lights}" + (" + emissive meshes" if self.mesh_lights else ""))
        if self.world:
            parts.append("world")
        parts.append("NEE+BSDF MIS" if use_mis else "NEE only (no MIS)")
        if self.see_through_films:
            parts.append("see-through film shadows")
        if self.features:
            parts.append("materials: " + ", ".join(self.features))
        parts.append(f"{pixel_filter} filter")
        if self.camera_strategy:
            parts.append(self.camera_strategy)
        return " | ".join(parts)


def analyse(scene, settings, bsdfs, camera) -> SceneAnalysis:
    """Inspect the scene and its built BSDFs / camera model."""
    used = sorted(int(m) for m in np.unique(np.asarray(scene.triangle_material))) if len(scene.triangles) else []
    if used and (used[0] < 0 or used[-1] >= len(scene.materials)):
        raise PrismInputError("Scene triangles reference a material index that does not exist: re-export the scene.")
    k = int(settings.wavelengths_per_path) if settings.wavelength_mode == "cie" else 3
    a = SceneAnalysis(settings.wavelength_mode, k, used)
    features = set()
    for m in used:
        b = bsdfs[m]
        mat = scene.materials[m]
        if b.disperses:
            a.dispersive.append(mat.glass or mat.name)
        if is_emissive(mat):
            a.mesh_lights = True
        if b.kind in ("conductor", "dielectric"):
            features.add(("mirror " if b.kind == "conductor" else "smooth ") + b.kind if b.delta else "rough " + b.kind)
        else:
            features.add(b.kind)
        if mat.kind in ("conductor", "dielectric") and mat.coating_thickness_nm > 0:
            features.add("thin-film coating")
        if b.kind == "thin_film":
            a.see_through_films = True
    a.camera_disperses = bool(getattr(camera, "disperses", False))
    a.camera_strategy = str(getattr(camera, "strategy", "") or "")
    a.dispersion = bool(a.dispersive) or a.camera_disperses
    a.light_kinds = [light.kind for light in scene.lights]
    a.features = sorted(features)
    a.world = scene.world.strength > 0 and max(scene.world.color) > 0
    return a
