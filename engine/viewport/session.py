"""One rendered viewport: what ``PrismRenderEngine.view_update`` and ``view_draw`` hand over to.

``view_update`` (a depsgraph change) exports what changed (``scene_sync``), the settings and the scene
camera; ``view_draw`` (every redraw) notices a new view (navigation, region size, camera view, render
border) and draws the latest image. Both post what changed to the ``ProgressiveRender`` thread, which
restarts the image at once. The render thread only calls ``tag_redraw`` on the engine, through a weak
reference: the engine's lifetime stays Blender's. When Blender frees the engine (Esc, leaving
Rendered mode, closing the area) a finalizer stops the thread; ``unregister`` stops every session.

Imported when a viewport first renders (it pulls in the tracer), never by ``register()``.
"""

from __future__ import annotations

import traceback
import weakref

from ..warmup import kernel_cache

kernel_cache.configure()  # before anything below imports a tracer kernel module

from ..export.camera import export_camera  # noqa: E402
from ..render.stats import stats_line  # noqa: E402
from ..tracer.errors import PrismInputError  # noqa: E402
from .display import FrameDisplay  # noqa: E402
from .progressive import Change, ProgressiveRender  # noqa: E402
from .scene_sync import SceneSync, Updates, classify, same  # noqa: E402
from .settings import viewport_settings  # noqa: E402
from .view import view_camera, view_of  # noqa: E402

#: Seconds ``view_draw``'s caller may wait for the render thread when the engine goes (a chunk in
#: flight finishes first; the thread is a daemon and ends on its own if it takes longer).
STOP_WAIT_S = 2.0

_live: weakref.WeakSet = weakref.WeakSet()


def _tag_redraw(engine_ref) -> None:
    engine = engine_ref()
    if engine is not None:
        try:
            engine.tag_redraw()  # sets a flag Blender's window manager polls: safe from this thread
        except ReferenceError:
            pass  # freed by Blender meanwhile


class ViewportSession:
    """The session of one engine (one 3D viewport region in Rendered mode)."""

    def __init__(self, engine):
        self._compiling = kernel_cache.compiling_notice()
        self._render = ProgressiveRender(on_frame=lambda ref=weakref.ref(engine): _tag_redraw(ref),
                                         describe=self._describe)
        self._sync = SceneSync()
        self._display = FrameDisplay()
        self._settings = None  # ViewportSettings last posted
        self._scene_camera = None
        self._camera_error: str | None = None
        self._view = None
        self._posted_view = None
        self._unposted = Change()
        self._export_error: str | None = None
        self._view_error: str | None = None
        self._settings_error: str | None = None
        self._shown_status = None
        _live.add(self)
        weakref.finalize(engine, self.stop, True, STOP_WAIT_S)

    # ---- what the engine hands over ----------------------------------------------------------
    def view_update(self, context, depsgraph) -> None:
        """A depsgraph change (and the first display): export what changed."""
        updates = classify(depsgraph) if self._sync.scene is not None else Updates.everything()
        change = Change()
        try:
            scene, geometry = self._sync.update(depsgraph, updates)
            if scene is not None:
                change.scene, change.geometry = scene, geometry
            if updates.camera or updates.scene or self._scene_camera is None:
                self._export_scene_camera(depsgraph)
            self._export_error = None
        except PrismInputError as error:
            self._export_error = str(error)
            return
        except Exception as error:  # noqa: BLE001 - a viewport must not raise into Blender
            traceback.print_exc()
            self._export_error = f"Prism failed unexpectedly ({type(error).__name__}: {error}); see the console."
            return
        self._post(change, context, depsgraph.scene, force_view=updates.camera or updates.scene)

    def view_draw(self, engine, context, depsgraph) -> None:
        """A redraw: notice a new view or new settings, show the status and the latest image."""
        self.sync_view(context, depsgraph)
        self._show_status(engine)
        if self.error is None:
            self._display.draw(engine, depsgraph.scene, self._render.frame, context.region.width,
                               context.region.height)

    def sync_view(self, context, depsgraph) -> None:
        """Post the view (navigation, region size, camera view, border) and the viewport settings
        when they differ from the last ones (setting changes redraw without a depsgraph update)."""
        if self._export_error is None:
            self._post(Change(), context, depsgraph.scene)

    @property
    def error(self) -> str | None:
        """Why the viewport shows nothing (the scene, the view or the render cannot be rendered)."""
        return self._scene_error() or self._render.error

    def _scene_error(self) -> str | None:
        return self._export_error or self._settings_error or self._view_error

    def stop(self, wait: bool = True, timeout: float = 30.0) -> None:
        """Stop the render thread (and with it the Renderer's threads)."""
        self._render.stop(wait, timeout)
        _live.discard(self)

    # ---- inside ---------------------------------------------------------------------------
    def _export_scene_camera(self, depsgraph) -> None:
        scene = depsgraph.scene
        self._scene_camera, self._camera_error = None, None
        if scene.camera is None:
            self._camera_error = f"Scene '{scene.name}' has no active camera to look through."
            return
        try:
            self._scene_camera = export_camera(scene, depsgraph)
        except PrismInputError as error:
            self._camera_error = str(error)

    def _post(self, change: Change, context, scene, force_view: bool = False) -> None:
        """Post ``change`` with the settings and the view's camera where they differ from the last
        (kept until then when the view or the settings cannot render)."""
        change = self._unposted = self._unposted.merged_with(change)
        try:
            settings = viewport_settings(scene)
        except PrismInputError as error:
            self._settings_error = str(error)
            return
        self._settings_error = None
        if self._settings is None or not same(settings.render, self._settings.render):
            change.settings = settings.render
        if self._settings is None or settings.samples != self._settings.samples:
            change.samples = settings.samples
        self._render.pause(settings.paused)
        self._settings = settings
        view = view_of(context, scene)
        if force_view or view != self._view:
            self._view = view
            try:
                if view.camera_view and self._scene_camera is None:
                    raise PrismInputError(self._camera_error or "The scene camera cannot render.")
                camera, border = view_camera(view, self._scene_camera if view.camera_view else None)
            except PrismInputError as error:
                self._view_error = str(error)
                return
            self._view_error = None
            if self._posted_view is None or not same((camera, border), self._posted_view):
                change.camera, change.border = camera, border
                self._posted_view = (camera, border)
        if any(value is not None for value in (change.scene, change.camera, change.settings, change.samples)):
            self._render.update(change)
        self._unposted = Change()

    def _describe(self, renderer, passes, done, target, seconds) -> str:
        if self._compiling:  # a pass finished: what it needed is compiled and cached, as after an F12 render
            self._compiling = None
            kernel_cache.mark_compiled()
        return stats_line(renderer, passes, done, target, seconds, self._sync.warnings)

    def status(self) -> str:
        """The line for the viewport header."""
        error = self._scene_error()
        if error is not None:
            return f"Prism | {error}"
        line = self._render.status
        if self._render.paused:
            line = f"{line} | Paused"
        if self._compiling and self._render.frame is None:
            line = f"{line} | {self._compiling}"
        return line

    def _show_status(self, engine) -> None:
        line = self.status()
        if line != self._shown_status:
            engine.update_stats("", line)
            self._shown_status = line

    @property
    def render(self) -> ProgressiveRender:
        return self._render

    @property
    def sync(self) -> SceneSync:
        return self._sync


def session_of(engine) -> ViewportSession:
    """The engine's viewport session, created on its first use."""
    session = getattr(engine, "_prism_viewport", None)
    if session is None:
        session = engine._prism_viewport = ViewportSession(engine)
    return session


def stop_all() -> None:
    """Stop every viewport session (the add-on is unregistering)."""
    for session in list(_live):
        session.stop()
