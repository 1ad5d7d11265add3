"""A ``Renderer`` refined by a background thread while its owner keeps posting changes.

No bpy: the Blender viewport session feeds it tracer scenes and cameras, and the viewport benchmark
drives it the same way outside Blender.

    render = ProgressiveRender(on_frame=callback)
    render.update(Change(scene=..., geometry=True, camera=..., settings=..., samples=0))
    frame = render.frame          # latest Frame (RGBA float32, rows bottom-up), or None
    render.status, render.error   # the stats line; a message when the scene cannot render
    render.pause(True / False)
    render.stop()                 # the thread and the Renderer's pool are gone when it returns

``update`` cancels the pass in progress (its queued chunks are dropped) and the thread applies the
change through the Renderer's ``set_*`` methods, so only the tables a change touches are rebuilt.
After every change the image starts coarse, one sample at a fraction of the resolution
(``COARSE_DIVIDERS``), and then refines at full resolution until ``samples`` (0: until stopped).
"""

from __future__ import annotations

import threading
import time
import traceback
from dataclasses import dataclass, replace

import numpy as np

#: Resolution dividers of the first images after a change, one sample each, coarsest first; a level
#: whose image would be smaller than ``COARSE_MIN_PIXELS`` on its short side is skipped.
COARSE_DIVIDERS = (4, 2)
COARSE_MIN_PIXELS = 16
#: A full-resolution pass traces at least about this many paths (small views take several samples a
#: pass: fewer passes, same refresh rate).
PASS_PATHS = 1 << 16
MAX_SAMPLES_PER_PASS = 16
UNLIMITED_SAMPLES = 1 << 30
THREAD_NAME = "Prism viewport"


@dataclass
class Change:
    """What changed since the last ``update``; None keeps what the render already has.

    ``scene``: a tracer ``Scene`` (its camera is ignored), with ``geometry`` True when its triangles
    differ from the last scene's (else only materials, lights and world changed). ``camera``: the
    view as a tracer ``Camera`` at full resolution, with ``border`` (pixels of that resolution, None:
    the whole view). ``settings``: ``RenderSettings`` (its ``samples`` and ``border`` are ignored).
    ``samples``: samples per pixel to stop at, 0 to go on until stopped.
    """

    scene: object = None
    geometry: bool = False
    camera: object = None
    border: tuple | None = None
    settings: object = None
    samples: int | None = None

    def merged_with(self, later: Change) -> Change:
        """This change followed by ``later``, as one."""
        camera_given = later.camera is not None
        return Change(
            scene=later.scene if later.scene is not None else self.scene,
            geometry=self.geometry or later.geometry,
            camera=later.camera if camera_given else self.camera,
            border=later.border if camera_given else self.border,
            settings=later.settings if later.settings is not None else self.settings,
            samples=later.samples if later.samples is not None else self.samples,
        )


@dataclass(frozen=True)
class Frame:
    """One published image: ``rgba`` float32 [height, width, 4] scene-linear, row 0 at the bottom,
    alpha 0 where no sample landed (outside the border); ``samples`` per pixel; ``divider`` 1 at full
    resolution; ``change`` the number of the last ``update`` it includes; ``time`` (perf_counter s)."""

    rgba: np.ndarray
    samples: int
    divider: int
    change: int
    time: float

    @property
    def width(self) -> int:
        return int(self.rgba.shape[1])

    @property
    def height(self) -> int:
        return int(self.rgba.shape[0])


def rgba_bottom_up(renderer) -> np.ndarray:
    """The renderer's mean image as float32 RGBA, first row at the bottom (as GPU textures are)."""
    rgb = renderer.image_rgb()
    rgba = np.empty((*rgb.shape[:2], 4), np.float32)
    rgba[..., :3] = rgb[::-1]
    rgba[..., 3] = renderer.sample_counts()[::-1] > 0
    return rgba


def _scaled_border(border, divider):
    if border is None:
        return None
    x0, y0, x1, y1 = border
    return x0 // divider, y0 // divider, -(-x1 // divider), -(-y1 // divider)


class ProgressiveRender:
    """See the module docstring. ``on_frame()`` is called from the render thread after each new frame
    (and after an error); ``describe(renderer, passes, samples, target, seconds)`` makes ``status``."""

    def __init__(self, on_frame=None, describe=None):
        self._on_frame = on_frame or (lambda: None)
        self._describe = describe or (lambda renderer, passes, done, target, seconds: f"{done} spp")
        self._condition = threading.Condition()
        self._pending: Change | None = None
        self._changes = 0
        self._paused = False
        self._stopping = False
        self._wanted = Change(samples=0)
        self._renderer = None
        self._ladder: list[int] = []
        self._passes = 0
        self._started = 0.0
        self._applied = 0
        self.frame: Frame | None = None
        self.status = "Prism | Preparing"
        self.error: str | None = None
        self._thread = threading.Thread(target=self._run, name=THREAD_NAME, daemon=True)
        self._thread.start()

    # ---- the owner's side (any thread) -------------------------------------------------------
    def update(self, change: Change) -> int:
        """Post ``change``; returns its number (``Frame.change`` reaches it once it is shown)."""
        with self._condition:
            self._pending = change if self._pending is None else self._pending.merged_with(change)
            self._changes += 1
            number = self._changes
            self._condition.notify_all()
        renderer = self._renderer
        if renderer is not None:
            renderer.cancel()
        return number

    def pause(self, paused: bool) -> None:
        """Stop refining after the pass in progress (changes wait too) or go on."""
        with self._condition:
            self._paused = bool(paused)
            self._condition.notify_all()

    @property
    def paused(self) -> bool:
        return self._paused

    @property
    def running(self) -> bool:
        return self._thread.is_alive()

    def stop(self, wait: bool = True, timeout: float = 30.0) -> None:
        """End the thread: the pass in progress is cancelled, the Renderer closed. Safe from any thread
        and more than once; ``wait`` joins the thread (never from the thread itself)."""
        with self._condition:
            self._stopping = True
            self._condition.notify_all()
        renderer = self._renderer
        if renderer is not None:
            renderer.cancel()
        if wait and threading.current_thread() is not self._thread:
            self._thread.join(timeout)

    # ---- the render thread ----------------------------------------------------------------
    def _run(self) -> None:
        try:
            while True:
                with self._condition:
                    while not self._stopping and (self._paused or (self._pending is None and not self._has_work())):
                        self._condition.wait()
                    if self._stopping:
                        return
                    change, self._pending = self._pending, None
                    number = self._changes
                try:
                    if change is not None:
                        self._apply(change, number)
                    else:
                        self._step()
                except Exception as error:  # noqa: BLE001 - shown in the viewport, the thread goes on
                    self._fail(error)
        finally:
            self._close_renderer()

    def _has_work(self) -> bool:
        if self._renderer is None or self.error is not None or not self._ladder:
            return False
        target = self._wanted.samples
        return self._ladder[0] != 1 or not target or self._renderer.samples_done < target

    def _apply(self, change: Change, number: int) -> None:
        wanted = self._wanted = self._wanted.merged_with(change)
        self._applied = number
        if wanted.scene is None or wanted.camera is None or wanted.settings is None:
            return  # not everything has arrived yet
        width, height = wanted.camera.resolution
        self._ladder = [d for d in COARSE_DIVIDERS if min(width, height) // d >= COARSE_MIN_PIXELS] + [1]
        self._passes = 0
        self._started = time.perf_counter()
        camera, border = self._level_view()
        settings = replace(wanted.settings, samples=UNLIMITED_SAMPLES, samples_per_pass=1, border=border)
        renderer = self._renderer
        if renderer is None or self.error is not None:
            from ..tracer.renderer import Renderer

            self._close_renderer()
            self.error = None
            self.status = "Prism | Preparing (BVH, spectra)"
            self._on_frame()
            self._renderer = Renderer(replace(wanted.scene, camera=camera), settings)
            return
        try:
            if change.settings is not None:
                renderer.set_settings(settings)
            if change.scene is not None:
                (renderer.set_geometry if change.geometry else renderer.set_shading)(wanted.scene)
            renderer.set_camera(camera, border)
        except Exception:
            self._close_renderer()  # half updated: the next change builds a new one
            raise

    def _level_view(self):
        """The camera and border of the ladder's current level."""
        divider = self._ladder[0]
        camera = self._wanted.camera
        width, height = camera.resolution
        size = (max(1, -(-width // divider)), max(1, -(-height // divider)))
        return replace(camera, resolution=size), _scaled_border(self._wanted.border, divider)

    def _step(self) -> None:
        renderer = self._renderer
        divider = self._ladder[0]
        per_pass = 1
        if divider == 1:
            per_pass = int(np.clip(PASS_PATHS // max(renderer.width * renderer.height, 1), 1, MAX_SAMPLES_PER_PASS))
            if self._wanted.samples:
                per_pass = min(per_pass, self._wanted.samples - renderer.samples_done)
        renderer.render_pass(per_pass)
        if renderer.cancelled:
            return  # a change is waiting (or the thread is stopping)
        self._passes += 1
        self._publish(divider)
        if divider != 1:
            self._ladder.pop(0)
            renderer.set_camera(*self._level_view())

    def _publish(self, divider: int) -> None:
        renderer = self._renderer
        target = self._wanted.samples or None
        status = self._describe(renderer, self._passes, renderer.samples_done, target,
                                time.perf_counter() - self._started)
        self.frame = Frame(rgba_bottom_up(renderer), renderer.samples_done, divider, self._applied,
                           time.perf_counter())
        self.status = status
        self._on_frame()

    def _fail(self, error: Exception) -> None:
        from ..tracer.errors import PrismInputError

        if isinstance(error, PrismInputError):
            message = str(error)
        else:
            traceback.print_exc()
            message = f"Prism failed unexpectedly ({type(error).__name__}: {error}); details are in the console."
        self.error = message
        self.status = f"Prism | {message}"
        self.frame = None
        self._ladder = []
        self._on_frame()

    def _close_renderer(self) -> None:
        renderer, self._renderer = self._renderer, None
        if renderer is not None:
            renderer.close()
