"""The scene's tables: everything the paths of a render read besides the camera and the film.

    tables = SceneTables(scene, settings, camera)   # geometry, Embree, shading, analysis
    tables.rebuild(scene, settings, camera)         # all again (new triangles, or a new origin)
    tables.rebuild_shading(scene, settings, camera) # materials, lights, world, settings; same triangles
    tables.describe(scene, settings, camera)        # the analysis again (a new camera, same origin)

Every position is relative to the render's origin (``camera.origin``). The tables are

- ``geometry`` (``geometry.prepare_geometry``: float32 triangles, zero-area ones dropped), its Embree
  scene ``accel`` and, when objects hide from some rays, ``ray_classes`` (else None);
- ``spectra`` (``spectra.table``), ``material_table`` (``materials.table``), ``light_table``
  (``lights.table``), ``pass_layout`` and ``aov_table`` (``pass_table``), the wavelength sampling
  ``wavelengths`` (guided by ``guide`` towards the scene's emission lines in ``cie`` mode, else None),
  ``kernel_settings`` (``stages.settings``) and ``needs_alpha`` (the film keeps alpha);
- what the scene needs (``analysis.analyse_scene``): ``analysis``, ``caustic_targets`` (None without
  light tracing) and the one-line ``strategy``;
- ``dropped_triangles``: how many zero-area triangles were left out;
- ``arrays``: the tables compiled bounce loops read, as one record (``stages.bounce_loop.SceneArrays``).
"""

from __future__ import annotations

import numpy as np

from .accel import Accel
from .analysis import analyse_scene
from .data_passes import first_hit_tables
from .materials.light_path import reads_light_path
from .media.enclosure import enclosing_media
from .media.equiangular import has_positional_lights
from .media.nesting import scene_overlaps
from .errors import PrismInputError
from .geometry import prepare_geometry
from .materials.displacement import displace, displaces
from .lights.emitters import emitter_spectra
from .lights.table import build_lights
from .materials.table import build_materials
from .pass_table import FilmLayout, aov_registers, aov_table
from .sampler import SAMPLERS
from .scene import SpectrumSpec
from .spectra import wavelength_sampling
from .spectra.table import SpectrumTable
from .spectra.wavelength_guide import build_guide
from .curves import curve_count
from .spheres import rendered_rows
from .stages.bounce_loop import SceneArrays
from .stages.camera import ORTHOGRAPHIC
from .stages.settings import KernelSettings
from .visibility import HOLDOUT, SHADOW_CATCHER
from .visibility_accel import RayClassAccel, needs_ray_classes


def _triangle_groups(scene, original_triangle, light_groups):
    """Light group index [T] of each render triangle's object (None when no group has a pass)."""
    if not light_groups or scene.triangle_object is None or not scene.object_light_groups:
        return None
    index = {name: g for g, name in enumerate(light_groups)}
    of_object = np.array([index.get(name, -1) for name in scene.object_light_groups], np.int32)
    return of_object[np.asarray(scene.triangle_object)[original_triangle]]


def _sphere_pass_index(scene):
    """Object ▸ Pass Index of each rendered sphere, then of each curve segment (float32 [S + C]; empty
    without point clouds and hair)."""
    points = getattr(scene, "points", None)
    rows = rendered_rows(points)
    spheres = (np.zeros(len(rows), np.float32) if not len(rows) or points.pass_index is None
               else np.asarray(points.pass_index, np.float32)[rows])
    curves = getattr(scene, "curves", None)
    count = curve_count(curves)
    segments = (np.zeros(count, np.float32) if not count or curves.pass_index is None
                else np.asarray(curves.pass_index, np.float32))
    return np.concatenate([spheres, segments])


def _kept(triangle_object, original):
    """The object of each kept triangle (``original``: their indices before dropping), or None."""
    if triangle_object is None:
        return None
    return np.asarray(triangle_object)[original]


def _row_objects(scene, original):
    """The object of each render row: the kept triangles', then the rendered spheres', then the curve
    segments' (so light and shadow linking read a sphere or curve hit's object as a triangle's), or None."""
    kept = _kept(scene.triangle_object, original)
    rows = rendered_rows(getattr(scene, "points", None))
    curves = getattr(scene, "curves", None)
    if kept is None or not (len(rows) or curve_count(curves)):
        return kept
    parts = [kept]
    if len(rows):
        parts.append(np.asarray(scene.points.object)[rows])
    if curve_count(curves):
        parts.append(np.asarray(curves.object))
    return np.concatenate(parts).astype(kept.dtype)


def _trick_settings(tricks, max_bounces) -> dict:
    """The ``KernelSettings`` fields of Cycles' Light Paths tricks (``path_tricks``)."""
    direct, indirect = tricks.kernel_limits()
    return dict(clamping=tricks.clamping, clamp_direct=direct, clamp_indirect=indirect,
                kind_limits=tricks.limits_kinds(max_bounces), bounce_limits=tricks.bounce_limits(max_bounces),
                caustics_filtered=tricks.caustics_filtered, caustics_reflective=bool(tricks.caustics_reflective),
                caustics_refractive=bool(tricks.caustics_refractive),
                filter_glossy=1.0 / tricks.filter_glossy if tricks.filter_glossy > 0.0 else 0.0)


def _linking_settings(lights) -> dict:
    """The ``KernelSettings`` flags of light and shadow linking (``light_linking``): on only where some
    emitter of the render (a light row, an emissive triangle) is linked."""
    from .light_linking import ALL_SETS

    links = lights.links
    if not len(links.receiver_set):
        return dict(light_linking=False, shadow_linking=False)
    emitting = lights.mesh.triangle
    light = bool((links.row_light_sets != ALL_SETS).any() or (links.triangle_light_sets[emitting] != ALL_SETS).any())
    shadow = bool((links.row_shadow_sets != ALL_SETS).any()
                  or (links.triangle_shadow_sets[emitting] != ALL_SETS).any())
    return dict(light_linking=light, shadow_linking=shadow)


class SceneTables:
    """The tables of ``scene`` rendered with ``settings`` from ``camera`` (a ``cameras`` camera, whose
    ``origin`` the positions are relative to). Rebuild them only while no pass runs."""

    def __init__(self, scene, settings, camera):
        self.geometry = self.accel = self.ray_classes = None
        self.rebuild(scene, settings, camera)

    def rebuild(self, scene, settings, camera) -> None:
        """All tables again: triangles relative to ``camera.origin``, their Embree scene, shading, analysis."""
        self._build_geometry(scene, camera.origin)
        self.rebuild_shading(scene, settings, camera)

    def _build_geometry(self, scene, origin) -> None:
        """Triangles relative to ``origin`` (m) and their Embree scene."""
        self.geometry = self.accel = self.ray_classes = None  # the old tables go first: one BVH in memory at a time
        self.geometry, self._original_triangle, self.dropped_triangles = prepare_geometry(scene, origin)
        if displaces(scene):  # Displacement Only / Both: the vertices move before Embree sees them
            used = sorted(set(np.unique(self.geometry.material).tolist()))
            table = build_materials(scene.materials, set(used), SpectrumTable(), scene.world.medium)
            flat = scene.triangle_flat[self._original_triangle] if scene.triangle_flat is not None and len(
                scene.triangle_flat) == len(scene.triangles) else None
            self.geometry = displace(self.geometry, table, flat)
        self._used = sorted(set(np.unique(self.geometry.material).tolist()))
        self.accel = Accel(self.geometry)
        self.ray_classes = RayClassAccel(self.geometry, self.accel) if needs_ray_classes(self.geometry) else None

    def rebuild_shading(self, scene, settings, camera) -> None:
        """Everything the paths read besides the triangles and the camera: spectra, materials, lights,
        wavelength sampling, kernel settings; then the analysis (``describe``)."""
        used = self._used
        if used and (used[0] < 0 or used[-1] >= len(scene.materials)):
            raise PrismInputError("Scene triangles reference a material index that does not exist: re-export the scene.")
        spectra = SpectrumTable()
        self.material_table = build_materials(scene.materials, set(used), spectra, scene.world.medium, camera.origin,
                                              geometry=self.geometry, overlaps=scene_overlaps(scene))
        materials = self.material_table.arrays
        groups = tuple(settings.passes.light_groups)
        triangles = len(self.geometry.triangles)  # spheres and curves follow them in ``material``; none is light-sampled
        catcher = (self.geometry.flags & SHADOW_CATCHER) != 0  # every primitive (triangles, spheres, curves)
        has_catcher = bool(catcher.any())
        self.light_table = build_lights(scene, spectra, self.geometry.vertices, self.geometry.triangles,
                                        self.geometry.material[:triangles], materials.emission_strength, camera.origin,
                                        light_groups=groups,
                                        triangle_group=_triangle_groups(scene, self._original_triangle, groups),
                                        triangle_objects=_row_objects(scene, self._original_triangle),
                                        triangle_catcher=catcher if has_catcher else None)
        white = spectra.emission(SpectrumSpec(kind="rgb", rgb=(1.0, 1.0, 1.0))) if not settings.passes.empty else -1
        self.pass_layout = FilmLayout(settings.passes, white, catcher_objects=has_catcher)
        self.aov_table = aov_table(scene.materials, settings.passes.aovs)
        self.aov_registers = aov_registers(scene.materials, settings.passes.aovs)
        self.first_hit = first_hit_tables(scene.data_passes, self._original_triangle, len(scene.materials),
                                          self.pass_layout.kernel, camera.data.projection == ORTHOGRAPHIC,
                                          _sphere_pass_index(scene), _row_objects(scene, self._original_triangle))
        self.spectra = spectra.arrays()
        guide = None
        if settings.wavelength_mode == "cie":
            guide = build_guide(self.spectra, emitter_spectra(self.light_table, materials))
        self.wavelengths = wavelength_sampling.build(settings, guide)
        self.guide = guide
        has_media = bool((materials.medium >= 0).any()) or self.material_table.outside_medium >= 0
        self.kernel_settings = KernelSettings(
            max_bounces=int(settings.max_bounces), roulette_depth=int(settings.russian_roulette_depth),
            transparent_max_bounces=int(settings.transparent_max_bounces),
            use_mis=bool(settings.use_mis), sampler=SAMPLERS[settings.sampler], seed=int(settings.seed) & 0xFFFFFFFF,
            light_tracing=False,  # the analysis decides (``describe``)
            film_transparent=bool(settings.film_transparent),
            transparent_glass=bool(settings.film_transparent and settings.transparent_glass),
            transparent_alpha=float(settings.transparent_roughness) ** 2,
            **_trick_settings(settings.light_path_tricks, settings.max_bounces), wavelengths=self.wavelengths,
            has_media=has_media, outside_medium=int(self.material_table.outside_medium),
            camera_medium=self._camera_medium(scene, camera) if has_media else -1,
            equiangular=has_media and has_positional_lights(self.light_table.arrays),
            **_linking_settings(self.light_table.arrays), light_path=reads_light_path(materials),
            shadow_catcher=has_catcher)
        self.needs_alpha = (bool(settings.film_transparent) or bool((self.geometry.flags & HOLDOUT).any())
                            or has_catcher)
        self.describe(scene, settings, camera)

    def _camera_medium(self, scene, camera) -> int:
        """The ``media`` row camera rays start in: that of the media whose meshes enclose the camera, with the
        World's Volume (``media.nesting``; past what nests, the first alone: the export warns), else -1."""
        inside = enclosing_media(camera.position, scene.vertices, scene.triangles, scene.triangle_material,
                                 scene.materials)
        rows = self.material_table.nested_rows
        inside = [m for m in inside if frozenset((m,)) in rows]
        return int(rows.get(frozenset(inside), rows[frozenset(inside[:1])]))

    def describe(self, scene, settings, camera) -> None:
        """What the scene needs seen from ``camera``: ``analysis``, light tracing on or off (with its
        ``caustic_targets``) and the ``strategy`` line."""
        self.analysis, targets = analyse_scene(scene, settings, self._used, self.material_table, self.light_table,
                                               camera, self.geometry, self.pass_layout, self.ray_classes,
                                               _kept(scene.triangle_object, self._original_triangle))
        if self.guide is not None:
            a, guide = self.analysis, self.guide
            a.guided_lines, a.guided_measured, a.guided_smooth = guide.lines, guide.measured, guide.smooth
        self.kernel_settings = self.kernel_settings._replace(light_tracing=bool(self.analysis.light_tracing))
        self.caustic_targets = targets if self.analysis.light_tracing else None
        self.strategy = self.analysis.strategy(settings.use_mis, settings.pixel_filter)
        self.arrays = SceneArrays(self.geometry, self.material_table.arrays, self.light_table.arrays, self.spectra,
                                  self.kernel_settings, self.wavelengths)
