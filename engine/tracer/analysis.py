"""Scene analysis: decide before tracing what the scene needs, and say so in one line.

- Hero-wavelength termination only if a used glass disperses or the camera does (a real lens);
  otherwise every path carries all its wavelengths to the end.
- Emissive meshes are light-sampled only if some used material emits.
- Shadow rays cross free-standing films and cut-outs only if the scene has one (else one occlusion query
  each).
- Wavelength sampling (cie mode) follows the scene's emission spectra; the visible density only when
  nothing emits.
- Caustics come from light tracing (``choose_light_tracing``) only if a smooth glass or mirror can
  focus a small light (``lights.apparent_size``) onto a surface that is not purely specular, seen
  through a pinhole or thin lens.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .lights.apparent_size import small_lights
from .lights.caustic_targets import build_caustic_targets
from .materials.light_path import reads_light_path
from .materials.shader_rays import traces_rays
from .materials.table import MAT_DELTA, MAT_DISPERSIVE, MAT_EMISSIVE, MAT_NULL, MAT_SUBSURFACE, MAT_TRANSPARENT
from .stages.camera import ORTHOGRAPHIC, PERSPECTIVE
from .visibility import HOLDOUT, SHADOW_CATCHER


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
    world: str = ""
    guided_lines: int = 0
    guided_measured: int = 0
    guided_smooth: int = 0
    camera_strategy: str = ""
    see_through_films: bool = False
    see_through_cutouts: bool = False
    sampler: str = "sobol"
    light_tracing: bool = False
    light_tracing_note: str = ""  # what the stats line says about light tracing
    motion_note: str = ""  # motion blur: what moves, in how many time steps

    def strategy(self, use_mis: bool, pixel_filter: str) -> str:
        """One line for the render stats."""
        parts = [f"{self.wavelength_mode} x{self.wavelengths_per_path}"]
        counts = ((self.guided_lines, "emission line(s)"), (self.guided_measured, "measured spectrum(s)"),
                  (self.guided_smooth, "smooth spectrum(s)"))
        guides = [f"{count} {what}" for count, what in counts if count]
        if guides:
            parts[0] += " guided by " + " + ".join(guides)
        if self.dispersion:
            what = ", ".join(self.dispersive + (["lens"] if self.camera_disperses else []))
            parts.append(f"hero-wavelength termination ({what})")
        else:
            parts.append("no dispersion: all wavelengths kept")
        lights = ", ".join(sorted(set(k for k in self.light_kinds if k != "emissive meshes"))) or "none"
        parts.append(f"lights: {lights}" + (" + emissive meshes" if self.mesh_lights else ""))
        if self.world:
            parts.append(self.world)
        parts.append("NEE+BSDF MIS" if use_mis else "NEE only (no MIS)")
        if self.see_through_films:
            parts.append("see-through film shadows")
        if self.see_through_cutouts:
            parts.append("see-through cut-out shadows")
        if self.features:
            parts.append("materials: " + ", ".join(self.features))
        parts.append(f"{pixel_filter} filter")
        parts.append(f"{self.sampler} sampler")
        if self.camera_strategy:
            parts.append(self.camera_strategy)
        if self.motion_note:
            parts.append(self.motion_note)
        if self.light_tracing_note:
            parts.append(self.light_tracing_note)
        return " | ".join(parts)


def choose_light_tracing(mode: str, specular: list[str], films: list[str], receivers: bool, small_lights: list[str],
                         lights: bool, path_tracing_only: str = "") -> tuple[bool, str]:
    """(trace caustics from the lights?, the stats line's words) for the setting ``mode`` ("auto", "off",
    "on"). ``specular``: names of the purely specular materials that can focus light (smooth glass,
    mirrors); ``films``: free-standing films (they count only when forced on); ``receivers``: some
    surface is not purely specular; ``small_lights``: lights that look small from the specular objects
    (``lights.apparent_size``: path tracing alone would not find their caustics); ``lights``: some
    light other than the world emits; ``path_tracing_only``: why this render cannot light-trace
    ("real lens": connections do not go through lens systems; "spectral output": the spectral film
    takes camera samples only), "" if it can. Auto needs a small light: a large one's caustics path
    tracing finds by itself, and light paths would only take time from the rest of the image."""
    if mode == "off":
        return False, "light tracing off"
    focusing = specular + (films if mode == "on" else [])
    if path_tracing_only:
        return False, f"caustics by path tracing ({path_tracing_only})"
    if not (focusing and receivers and lights):
        return False, "no caustics to light-trace" if mode == "auto" else "light tracing on, but nothing to trace"
    if mode == "auto" and not small_lights:
        return False, "caustics by path tracing (lights large enough)"
    return True, f"caustics by light tracing ({', '.join(focusing)})"


def analyse_scene(scene, settings, used, material_table, light_table, camera, geometry, pass_layout, ray_classes,
                  triangle_objects):
    """(``SceneAnalysis`` of a render, the caustic targets of its specular triangles or None) from its
    tables: ``used`` material indices, ``camera`` (``cameras.make_camera``), ``geometry`` (its triangles),
    ``pass_layout`` (``pass_table.FilmLayout``), ``ray_classes`` (None unless some object hides from some ray
    type), ``triangle_objects`` (the object of each triangle, or None)."""
    k = int(settings.wavelengths_per_path) if settings.wavelength_mode == "cie" else 3
    a = SceneAnalysis(settings.wavelength_mode, k, list(used), sampler=settings.sampler)
    flags = material_table.arrays.flags
    for m in used:
        if flags[m] & MAT_DISPERSIVE:
            material = scene.materials[m]
            a.dispersive.append(material.glass or material.name)
    a.mesh_lights = any(flags[m] & MAT_EMISSIVE for m in used)
    a.see_through_films = any(flags[m] & MAT_NULL for m in used)
    a.see_through_cutouts = any(flags[m] & MAT_TRANSPARENT for m in used)
    a.camera_disperses = camera.disperses
    a.camera_strategy = camera.strategy
    a.dispersion = bool(a.dispersive) or a.camera_disperses
    a.light_kinds = [light.kind for light in scene.lights]
    a.features = list(material_table.features)
    a.world = light_table.world
    specular, films = [], []
    for m in used:
        if flags[m] & MAT_DELTA:
            (films if flags[m] & MAT_NULL else specular).append(scene.materials[m].name)
    lights = light_table.arrays
    targets, small = None, []
    if specular or films:
        targets = build_caustic_targets(geometry, flags, MAT_DELTA, triangle_objects)
        small = small_lights(lights.rows[:len(light_table.names)], light_table.names, lights.mesh, targets)
    a.motion_note = _motion_note(camera, geometry)
    only = _path_tracing_only(settings, camera, geometry, pass_layout, ray_classes)
    if not only and ((material_table.arrays.medium >= 0).any() or material_table.outside_medium >= 0):
        only = "media"  # light paths do not track media
    if not only and len(lights.links.receiver_set):
        only = "light linking"  # light paths do not test light or shadow sets; path tracing honours them
    if not only and reads_light_path(material_table.arrays):
        only = "Light Path node"  # light paths carry no camera-path ray kinds; path tracing honours them
    if not only and traces_rays(material_table.arrays):
        only = "Ambient Occlusion or Bevel node"  # a light path's hits cannot trace a material's own rays
    if not only and any(flags[m] & MAT_SUBSURFACE for m in used):
        only = "subsurface scattering"  # light paths do not walk under surfaces
    a.light_tracing, a.light_tracing_note = choose_light_tracing(
        settings.light_tracing, specular, films, any(not flags[m] & MAT_DELTA for m in used), small,
        any(kind != "world" for kind in light_table.kinds), only)
    return a, targets


def _motion_note(camera, geometry) -> str:
    """The stats line's words on motion blur ("" for a still image)."""
    if camera.data.shutter_times.shape[0] == 0:
        return ""
    from .accel import moving_triangles
    from .curves import moving_segments
    from .spheres import moving_spheres

    moving = moving_triangles(geometry)
    what = [f"{int(moving.sum())} moving triangles x{geometry.motion.shape[0]} steps"] if moving is not None else []
    strands = moving_segments(geometry.curve_motion, geometry.curve_segments)
    if strands:
        what.append(f"{strands} moving curve segments x{geometry.curve_motion.shape[0]} steps")
    points = moving_spheres(geometry.sphere_motion)
    if points:
        what.append(f"{points} moving spheres x{geometry.sphere_motion.shape[0]} steps")
    if camera.data.poses.shape[0]:
        what.append("moving camera")
    return "motion blur (" + (", ".join(what) or "nothing moves") + ")"


def _path_tracing_only(settings, camera, geometry, pass_layout, ray_classes) -> str:
    """Why this render cannot trace light paths to the camera ("" if it can): connections reach a
    perspective camera's pinhole or lens only, and see every object as the camera does."""
    layout = pass_layout.kernel
    if camera.lens is not None:
        return "real lens"
    if camera.data.projection != PERSPECTIVE:
        return "orthographic camera" if camera.data.projection == ORTHOGRAPHIC else "panoramic camera"
    if settings.spectral_band_nm:
        return "spectral output"
    if layout.light >= 0 or layout.groups > 0:
        return "light passes"
    if settings.light_path_tricks.biased:
        return "clamps or caustics toggles"
    if settings.light_path_tricks.limits_kinds(settings.max_bounces):
        return "bounce limits per kind"  # light paths would have to count them from the camera's end
    if (geometry.flags & SHADOW_CATCHER).any():
        return "shadow catcher"  # light paths would have to split at it too (``stages.shadow_catcher``)
    if ray_classes is not None or (geometry.flags & HOLDOUT).any():
        return "ray visibility or holdouts"
    return ""
