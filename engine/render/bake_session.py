"""One bake (Render ▸ Bake with Prism as the engine): Blender's texels → rays → the tracer → baked values.

Blender calls ``RenderEngine.bake(depsgraph, object, pass_type, pass_filter, width, height)`` once per
image of the object (and, with Selected to Active, once per selected object, each with the texels whose
surface point is on it). Inside that call each ``begin_result(x, y, w, h, layer=...)`` returns a Render
Result for that rectangle of the image holding Blender's ``BakePrimitive`` pass (barycentric u, v and the
loop triangle's index as the bits of a float; -1 where the texel has no point on this object) and
``BakeDifferential``; what the engine writes into its ``Combined`` pass becomes the texels' values when the
result ends (texels without a point are left as they were; Blender adds the margin itself).

Prism exports the scene once, then bakes the image tile by tile (``BAKE_TILE_PX``: memory stays bounded
for any image size), each tile's rays starting at its texels' surface points (``bake_points``) and the
bake type's passes combined as Cycles combines them (``bake_types``). Progress through
``update_progress``, stopping through ``test_break``.
"""

from __future__ import annotations

import itertools
import time
import traceback

import numpy as np

from ..warmup import kernel_cache

kernel_cache.configure()  # before anything below imports a tracer kernel module

from ..export import export_scene  # noqa: E402
from ..export.settings import export_settings  # noqa: E402
from ..tracer.errors import PrismInputError  # noqa: E402
from ..tracer.pass_table import PASSES, PassRequest  # noqa: E402
from ..tracer.scene import Camera  # noqa: E402
from ..tracer.stages.bake_camera import BakeRays  # noqa: E402
from .bake_mesh import bake_triangles  # noqa: E402
from .bake_points import bake_ray_table, surface_points, towards_camera  # noqa: E402
from .bake_types import SUPPORTED, bake_recipe, baked_value, refusal  # noqa: E402

#: Texels a side of the tiles a bake renders one after another: the ray table and the film of one tile
#: (~0.1 KB a texel) are all Prism holds besides the scene, whatever the image's size.
BAKE_TILE_PX = 256
#: Blender matches each result to its image by the result's layer name: one name per ``bake`` call.
_LAYER_NUMBERS = itertools.count()
#: Cycles bakes every texel at the middle of the shutter.
BAKE_RAY_TIME = 0.5


class _Stopped(Exception):
    """The user stopped the bake (Esc)."""


def _bake_camera(triangles, width: int, height: int) -> Camera:
    """A camera that only places the render's origin, at the middle of the baked object (float32 geometry is
    kept precise around it); bake rays never come from it."""
    corners = triangles.corners.reshape(-1, 3)
    middle = (corners.min(axis=0) + corners.max(axis=0)) / 2.0 if len(corners) else np.zeros(3)
    to_world = np.eye(4)
    to_world[:3, 3] = middle
    return Camera(name="Bake", camera_to_world=to_world, resolution=(int(width), int(height)))


def _camera_view(scene, depsgraph, object_name: str):
    """Bake ▸ View From: None (Above Surface: each point seen along its normal) or, for Active Camera, the
    camera's (position, +Z axis when orthographic else None) in world space, m."""
    if scene.render.bake.view_from != "ACTIVE_CAMERA":
        return None
    camera = scene.camera
    if camera is None or camera.type != "CAMERA":
        raise PrismInputError(f"Object '{object_name}': Render ▸ Bake ▸ View From is Active Camera, but scene "
                              f"'{scene.name}' has no active camera: set one, or bake from Above Surface.")
    matrix = np.array(camera.evaluated_get(depsgraph).matrix_world, np.float64)
    axis = matrix[:3, 2] / np.linalg.norm(matrix[:3, 2]) if camera.data.type == "ORTHO" else None
    return matrix[:3, 3].copy(), axis


def _tiles(width: int, height: int):
    for y in range(0, height, BAKE_TILE_PX):
        for x in range(0, width, BAKE_TILE_PX):
            yield x, y, min(BAKE_TILE_PX, width - x), min(BAKE_TILE_PX, height - y)


class BakeSession:
    """Bakes ``pass_type`` (Blender's identifier, e.g. "COMBINED") with ``pass_filter`` (its bits) of
    ``bake_object`` into the ``width`` x ``height`` image Blender is baking, through ``engine``."""

    def __init__(self, engine, depsgraph, bake_object, pass_type: str, pass_filter: int, width: int, height: int):
        self.engine = engine
        self.depsgraph = depsgraph
        self.object = bake_object
        self.pass_type = pass_type
        self.pass_filter = int(pass_filter)
        self.width, self.height = int(width), int(height)
        self.error = None
        self.triangles = None  # the object's loop triangles (``bake_mesh``), read once per bake
        self.view = None  # where the texels are seen from (``_camera_view``)

    def run(self) -> None:
        try:
            self._bake()
        except _Stopped:
            self.engine.update_stats("", "Prism | Bake cancelled")
        except PrismInputError as error:
            self._fail(str(error))
        except MemoryError:
            self._fail("Prism ran out of memory while baking: lower the image's resolution or the thread count.")
        except Exception as error:  # noqa: BLE001 - a bug: one clear line in the report, details in the console
            traceback.print_exc()
            self._fail(f"Prism failed unexpectedly while baking ({type(error).__name__}: {error}); "
                       "details are in the console.")

    def _fail(self, message: str) -> None:
        self.error = message
        self.engine.error_set(message)
        self.engine.report({"ERROR"}, message)

    def _stop_requested(self) -> bool:
        return bool(self.engine.test_break())

    def _bake(self) -> None:
        from ..tracer.renderer import Renderer

        name = self.object.name
        refused = refusal(self.pass_type)
        if refused is not None:
            raise PrismInputError(f"Object '{name}': {refused}")
        recipe = bake_recipe(self.pass_type, self.pass_filter)
        engine = self.engine
        scene = self.depsgraph.scene
        kernel_cache.check_directory()
        compiling = kernel_cache.compiling_notice()
        notice = f" | {compiling}" if compiling else ""
        engine.update_stats("", f"Prism | Exporting scene for baking{notice}")
        evaluated = self.object if self.object.is_evaluated else self.object.evaluated_get(self.depsgraph)
        if not evaluated.visible_camera:  # Prism's bake rays are camera rays: they would pass through it
            raise PrismInputError(f"Object '{name}' is hidden from camera rays (Object ▸ Visibility ▸ Ray Visibility "
                                  "▸ Camera), and Prism bakes what camera rays see: turn Camera on to bake it.")
        triangles = self.triangles = bake_triangles(evaluated)
        self.view = _camera_view(scene, self.depsgraph, name)
        warnings: list[str] = []
        tracer_scene = export_scene(self.depsgraph, warnings, camera=_bake_camera(triangles, self.width, self.height),
                                    motion=False)
        if name not in tracer_scene.object_names:
            raise PrismInputError(f"Object '{name}' is not rendered (hidden from renders, filtered out of the view "
                                  "layer, or without faces), so Prism cannot bake it: make it renderable.")
        for message in warnings:
            engine.report({"WARNING"}, message)
        settings = export_settings(scene, passes=PassRequest(tuple(n for n in PASSES if n in recipe.passes)))
        # A bake samples every texel alike from its surface point: no light tracing (its paths reach the
        # film through a camera), no adaptive sampling or time limit, no spectral file.
        settings.light_tracing = "off"
        settings.adaptive_threshold = 0.0
        settings.time_limit_s = 0.0
        settings.spectral_band_nm = 0.0
        if recipe.first_hit_only:
            settings.max_bounces = 0
        settings.validate()
        layer = f"Prism bake {next(_LAYER_NUMBERS)}"
        tiles = list(_tiles(self.width, self.height))
        started = time.perf_counter()
        engine.update_stats("", f"Prism | Preparing the bake (BVH, spectra){notice}")
        with Renderer(tracer_scene, settings) as renderer:
            for index, tile in enumerate(tiles):
                self._bake_tile(renderer, recipe, tile, layer, (index, len(tiles)))
        if compiling:
            kernel_cache.mark_compiled()
        engine.update_progress(1.0)
        engine.update_stats("", f"Prism | Baked {SUPPORTED[self.pass_type]} of '{name}' "
                                f"({self.width} x {self.height}, {settings.samples} samples) in "
                                f"{time.perf_counter() - started:.1f} s")

    def _bake_tile(self, renderer, recipe, tile, layer, position) -> None:
        """Render one tile's texels and hand their values to Blender."""
        x, y, w, h = tile
        index, count = position
        if self._stop_requested():
            raise _Stopped
        result = self.engine.begin_result(x, y, w, h, layer=layer)
        stopped = False
        try:
            passes = result.layers[0].passes
            primitive_pass = np.empty(w * h * 3, np.float32)
            passes["BakePrimitive"].rect.foreach_get(primitive_pass)
            primitive_pass = primitive_pass.reshape(-1, 3)
            primitive = np.ascontiguousarray(primitive_pass[:, 2]).view(np.int32)
            texels = np.flatnonzero(primitive >= 0)
            if len(texels) == 0:
                return
            stopped = self._render_tile(renderer, tile, primitive_pass, primitive, texels, position)
            if not stopped:
                self._write(passes["Combined"], renderer, recipe, texels, w * h)
        finally:
            self.engine.end_result(result, cancel=stopped)
        self.engine.update_progress((index + 1) / count)
        if stopped:
            raise _Stopped

    def _render_tile(self, renderer, tile, primitive_pass, primitive, texels, position) -> bool:
        """Every sample of the tile's ``texels``; True when stopped."""
        x, y, w, h = tile
        index, count = position
        points = surface_points(self.triangles, primitive[texels], primitive_pass[texels, 0].astype(np.float64),
                                primitive_pass[texels, 1].astype(np.float64))
        seen_from = None if self.view is None else towards_camera(points, *self.view)
        origin, direction = bake_ray_table(points, renderer.origin, seen_from)
        table_origin = np.zeros((w * h, 3))
        table_direction = np.zeros((w * h, 3))
        table_origin[texels], table_direction[texels] = origin, direction
        rays = BakeRays(table_origin, table_direction, np.full(w * h, BAKE_RAY_TIME), x, y, w, self.width)
        renderer.set_region((x, y, x + w, y + h))
        rows, columns = np.divmod(texels, w)
        renderer.set_bake_rays(rays, (y + rows) * self.width + x + columns)
        target = renderer.settings.samples

        def progress(fraction):
            done = renderer.samples_done + fraction * renderer.settings.samples_per_pass
            self.engine.update_progress(min(1.0, (index + done / target) / count))
            if self._stop_requested():
                renderer.cancel()

        renderer.progress = progress
        while not renderer.finished:
            renderer.render_pass()
            if renderer.cancelled or self._stop_requested():
                return True
        return False

    def _write(self, combined, renderer, recipe, texels, size: int) -> None:
        """The baked values of the tile's texels into Blender's ``Combined`` pass (alpha 1), in its texel order."""
        images = renderer.pass_images()
        value = baked_value(recipe, renderer.film.mean(), images).reshape(-1, 3)
        out = np.zeros((size, combined.channels), np.float32)
        channels = min(3, combined.channels)
        out[texels, :channels] = value[texels, :channels]
        if combined.channels > 3:
            out[texels, 3] = 1.0
        combined.rect.foreach_set(out.ravel())
