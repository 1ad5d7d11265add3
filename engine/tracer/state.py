"""The state of a chunk of paths, declared once: ``PathState`` (one row per path) and the ray queues.

Paths never move: the queues hold path indices. A bounce's surviving paths are appended to the next
ray queue by the shading kernel, which is the compaction (one pass, in path order, so the work is
deterministic). Embree reads the queues' float32 rays directly.

``PathState`` fields (n paths, K wavelengths per path):

- ``pixel`` int64 (y · width + x), ``sample`` int64 (the sample's number in its pixel's sequence),
  ``seed`` int64 (the pixel's sampler seed);
- ``wavelength`` / ``wavelength_pdf`` float64 [n, K] (nm, 1/nm), ``hero`` int32 (the carried wavelength
  kept when the path meets dispersion);
- ``flags`` int32 (``COLLAPSED``: only the hero is carried, ×K; ``PREV_DELTA``: the last scattering was
  a delta lobe or the camera; ``SEEN_DIFFUSE`` / ``CAUSTIC`` / ``NOT_CAUSTIC``: where a camera path stands
  in the split with light tracing, ``stages.caustic_split``; ``LIGHT_SPECULAR`` / ``LIGHT_CONNECTED``:
  a light path's, ``stages.light_paths``; ``CAMERA_PATH``: the path still sees what the camera sees — no
  scattering yet but transparent glass — so the background and holdouts make it transparent;
  ``LAST_DIFFUSE``, ``LAST_TRANSMISSION``: what the last scattering was (neither: glossy), for ray
  visibility); ``MEDIUM_VERTEX``: this bounce's vertex is a collision in the path's medium at ``hit_t``
  along its ray, not a surface (``media.segment``); ``CATCHER_HIT``: the camera path met a shadow catcher
  and was split there (it goes on to Combined only); ``CATCHER_PASS``: the copy made at that split, which
  sees only shadow catchers and whose light goes to the catcher's accumulation (``stages.shadow_catcher``);
  ``SUBSURFACE_EXIT``: this bounce's vertex is where a subsurface random walk left the surface, its hit
  already in ``hit_*`` (``stages.subsurface``); ``PASSES_DONE``: the camera path has written the data passes of the
  first surface it met whose alpha reaches View Layer ▸ Alpha Threshold (Cycles' PATH_RAY_SINGLE_PASS_DONE,
  ``stages.data_pass_writes``); ``DIRECT_SAMPLED``: this bounce's light sampling lights a vertex before any scattering
  (its light is Direct in the passes, ``stages.pass_writes``);
- ``medium`` int32: the medium the path's ray travels in (``MaterialArrays.media`` row, -1: none);
- ``throughput`` and ``radiance`` float64 [n, K]; ``eta_scale`` float64 (Π eta'² of refractions, for
  Russian roulette); ``prev_pdf`` float64 (solid-angle pdf of the last BSDF sample); ``min_pdf`` float64
  (the smallest pdf of the path's non-specular bounces, inf before the first: Filter Glossy's measure);
- ``origin``, ``direction`` float64 [n, 3] (the current ray, camera-relative metres),
  ``mis_origin`` float64 [n, 3] (the last vertex that was not a null film crossing: light pdfs of
  emitters hit later are measured from it);
- ``hit_triangle`` int32, ``hit_u``, ``hit_v``, ``hit_t`` float64 (the hit handed from the emission
  stage to the shading stage);
- ``transparency`` float64 (how much of the sample is see-through: 1 - its alpha);
- ``time`` float64 (the path's ray time, 0..1 over the shutter as Embree reads it: every ray of the path —
  camera ray, bounces, shadow rays — sees the scene at this one instant; 0.5 without motion blur);
- ``receiver`` int64 (``light_linking``: the receiver light set of the path's last scattering vertex, -1 on
  camera rays; scattering vertices write it only in scenes with light or shadow linking);
- ``light_path`` int32 [n, RECORD] (``materials.light_path``: the kind of ray the path travels on and its bounce
  counts, for Blender's Light Path node and Cycles' per-kind bounce limits) and ``ray_travelled`` float64 (how
  far the ray came before the cut-outs and films it went straight through: its Ray Length counts from where it
  started, as Cycles' does); kept only in scenes whose materials read the node or that limit bounces by kind;
- ``crossings`` int32 [n, 2] (``stages.bounces``): the rays the path began by going straight through a surface
  (cut-outs, films, volume boundaries) rather than scattering, and of them its transparent bounces.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from .materials.light_path import RECORD
from .stages.bounces import CROSSINGS

COLLAPSED = 1
PREV_DELTA = 2
SEEN_DIFFUSE = 4
CAUSTIC = 8
NOT_CAUSTIC = 16
LIGHT_SPECULAR = 32
LIGHT_CONNECTED = 64
CAMERA_PATH = 128
LAST_DIFFUSE = 256
LAST_TRANSMISSION = 512
MEDIUM_VERTEX = 1024
CATCHER_HIT = 2048
CATCHER_PASS = 4096
SUBSURFACE_EXIT = 8192
PASSES_DONE = 16384
DIRECT_SAMPLED = 32768

_PATH_FIELDS = (
    ("pixel", np.int64, ()), ("sample", np.int64, ()), ("seed", np.int64, ()),
    ("wavelength", np.float64, ("K",)), ("wavelength_pdf", np.float64, ("K",)), ("hero", np.int32, ()),
    ("flags", np.int32, ()), ("medium", np.int32, ()),
    ("throughput", np.float64, ("K",)), ("radiance", np.float64, ("K",)),
    ("eta_scale", np.float64, ()), ("prev_pdf", np.float64, ()), ("min_pdf", np.float64, ()),
    ("origin", np.float64, (3,)), ("direction", np.float64, (3,)), ("mis_origin", np.float64, (3,)),
    ("hit_triangle", np.int32, ()), ("hit_u", np.float64, ()), ("hit_v", np.float64, ()), ("hit_t", np.float64, ()),
    ("transparency", np.float64, ()), ("time", np.float64, ()), ("receiver", np.int64, ()),
    ("light_path", np.int32, (RECORD,)), ("ray_travelled", np.float64, ()), ("crossings", np.int32, (CROSSINGS,)),
)
PathState = namedtuple("PathState", [name for name, _, _ in _PATH_FIELDS])

#: Rays for Embree: ``path`` int32 [n] (which path), ``origin`` / ``direction`` float32 [n, 3]
#: (camera-relative), ``tmax`` float32 [n] (shadow rays: where the light is), ``time`` float64 indexed by
#: *path* (the paths' ``PathState.time``, shared, so a queued ray needs no copy of its path's time).
RayQueue = namedtuple("RayQueue", "path origin direction tmax time")

#: Shadow rays and what each brings if it reaches its light: ``contribution`` float64 [n, K]; the
#: float64 ``origin`` / ``direction`` / ``distance`` let rays continue through free-standing films;
#: ``group`` int32 [n] the light group of the light sampled (for its pass); ``medium`` int32 [n] the medium
#: the shadow ray starts in (-1: none).
#: ``blockers`` int64 [n]: the blocker sets of the light sampled (``light_linking``; -1: every object blocks).
#: ``crossable`` int32 [n]: the cut-outs and films the ray may still cross (``stages.bounces.shadow_crossings``).
ShadowQueue = namedtuple("ShadowQueue", "rays contribution origin direction distance group medium blockers crossable")

#: Embree's answer for each queued ray: ``triangle`` int32 [n] (-1: a miss), ``t``, ``u``, ``v`` float32 [n].
HitRecord = namedtuple("HitRecord", "triangle t u v")

#: A worker thread's memory for one chunk (``ChunkBuffers.loop``, read by ``stages.bounce_loop``): ``rays``
#: the two ray queues (this bounce's, the next), ``hits`` a ``HitRecord`` per queued ray, ``occluded``
#: int32 per shadow ray, ``rejected`` the counter of rays dropped as non-finite, ``rgb`` the paths' colours.
LoopBuffers = namedtuple("LoopBuffers", "state rays surface shadows scratch hits occluded rejected rgb")

#: A list of paths (e.g. those that hit a surface this bounce).
PathList = namedtuple("PathList", "path")

#: Per-thread working memory of the shading kernel (kernels allocate nothing): the resolved closures of
#: one material (``rows`` [MAX_CLOSURES, CLOSURE_ROW], ``spectral`` [MAX_CLOSURES, 3, K], ``eta``
#: [MAX_CLOSURES]), spectral values [K] (``weight``, ``li``, ``f``, ``mix`` [2, K]) and the register
#: file of material programs (``registers``, as long as the render's largest program needs, and the Light Path
#: node's outputs after that: ``materials.light_path.FIELDS`` more) with the
#: closure rows an emitter's program may write while the vertex's are in use (``emitter_rows``).
ShadingScratch = namedtuple("ShadingScratch", "rows spectral eta weight li f mix registers emitter_rows")


def _shape(shape, n, k):
    return (n,) + tuple(k if s == "K" else s for s in shape)


def new_path_state(n: int, k: int) -> PathState:
    """Uninitialised storage for ``n`` paths of ``k`` wavelengths (the camera stage fills it)."""
    return PathState(*(np.empty(_shape(shape, n, k), dtype) for _, dtype, shape in _PATH_FIELDS))


def new_ray_queue(n: int, time=None) -> RayQueue:
    """A queue of ``n`` rays; ``time`` the paths' ray times (``PathState.time``; default 0.5 for each)."""
    # paths zeroed: a query reads its ray's time through ``path``, so no index may point outside ``time``
    return RayQueue(np.zeros(n, np.int32), np.empty((n, 3), np.float32), np.empty((n, 3), np.float32),
                    np.empty(n, np.float32), np.full(max(n, 1), 0.5) if time is None else time)


def new_shadow_queue(n: int, k: int, time=None) -> ShadowQueue:
    return ShadowQueue(new_ray_queue(n, time), np.empty((n, k)), np.empty((n, 3)), np.empty((n, 3)), np.empty(n),
                       np.empty(n, np.int32), np.full(n, -1, np.int32), np.full(n, -1, np.int64),
                       np.zeros(n, np.int32))


def new_shading_scratch(k: int, registers: int = 1) -> ShadingScratch:
    from .bsdf.closure import CLOSURE_ROW, MAX_CLOSURES
    from .materials.light_path import FIELDS

    return ShadingScratch(np.empty((MAX_CLOSURES, CLOSURE_ROW)), np.empty((MAX_CLOSURES, 3, k)),
                          np.empty(MAX_CLOSURES), np.empty(k), np.empty(k), np.empty(k), np.empty((2, k)),
                          np.zeros(max(int(registers), 1) + FIELDS), np.empty((MAX_CLOSURES, CLOSURE_ROW)))


class ChunkBuffers:
    """Everything one worker thread needs to trace a chunk of up to ``n`` paths (reused chunk after chunk)."""

    def __init__(self, n: int, k: int, passes=None, registers: int = 1):
        self.capacity = n
        self.k = k
        self.passes = passes  # stages.pass_writes.PassData
        self.state = new_path_state(n, k)
        self.rays = (new_ray_queue(n, self.state.time), new_ray_queue(n, self.state.time))  # this bounce's, the next
        self.surface = PathList(np.empty(n, np.int32))
        self.shadows = new_shadow_queue(n, k, self.state.time)
        self.scratch = new_shading_scratch(k, registers)
        self.rgb = np.empty((n, 3))
        self.alpha = np.empty(n)
        self.counters = np.zeros(1, np.int64)  # rays dropped as non-finite
        self.hits = HitRecord(np.empty(n, np.int32), np.empty(n, np.float32), np.empty(n, np.float32),
                              np.empty(n, np.float32))
        self.occluded = np.empty(n, np.int32)
        self._loop = None

    @property
    def loop(self):
        """These buffers as the bounce loop's record (``LoopBuffers``), made once."""
        if self._loop is None:
            self._loop = LoopBuffers(self.state, self.rays, self.surface, self.shadows, self.scratch, self.hits,
                                     self.occluded, self.counters, self.rgb)
        return self._loop
