"""A lens system (spherical surfaces, an aperture stop) and float64 ray tracing through it.

Lens coordinates, millimetres: the optical axis is +z, pointing from the scene toward the
film; the first (front) surface vertex is at z = 0 and each surface's ``thickness_mm`` is
the axial distance to the next one. A positive ``radius_mm`` puts the centre of curvature
on the film side of the vertex (a front surface that bulges toward the scene); ``inf`` is a
flat surface. ``medium`` of a surface fills the space after it (toward the film); the
scene side of the first surface and the film side of the last are air.

Tracing is vectorised over rays; the only Python loop is over surfaces. A ray that misses
a surface, falls outside its clear aperture (or the stop), or is totally internally
reflected dies with weight 0 and its fate is recorded.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from .media import AIR

FATE_ALIVE = 0
FATE_MISSED = 1  # the ray never meets the surface's sphere (or meets it behind itself)
FATE_BLOCKED = 2  # outside the clear aperture or the aperture stop
FATE_TIR = 3  # total internal reflection
FATE_NAMES = {FATE_ALIVE: "alive", FATE_MISSED: "missed", FATE_BLOCKED: "blocked", FATE_TIR: "TIR"}

TRACE_CHUNK = 16384

TOWARD_FILM = "film"
TOWARD_SCENE = "scene"


@dataclass(frozen=True)
class Surface:
    """One refracting surface or the aperture stop.

    ``radius_mm``: signed radius of curvature (inf = flat; the stop is flat).
    ``thickness_mm``: axial distance to the next surface toward the film.
    ``aperture_mm``: clear aperture DIAMETER. ``medium``: what fills the space after it.
    ``line``: line in the source file (for messages), if known.
    """

    radius_mm: float
    thickness_mm: float
    aperture_mm: float
    medium: object = AIR
    is_stop: bool = False
    line: int | None = None

    @property
    def curvature_per_mm(self) -> float:
        return 0.0 if self.is_stop or not np.isfinite(self.radius_mm) else 1.0 / self.radius_mm

    @property
    def semi_aperture_mm(self) -> float:
        return 0.5 * self.aperture_mm

    def sag_mm(self, r_mm):
        """Axial depth of the surface at height ``r_mm`` from its vertex (positive toward the film)."""
        c = self.curvature_per_mm
        r2 = np.asarray(r_mm, dtype=np.float64) ** 2
        with np.errstate(invalid="ignore"):
            return c * r2 / (1.0 + np.sqrt(1.0 - c * c * r2))


@dataclass
class TraceResult:
    """What happened to a batch of N rays.

    ``origins``/``directions`` [N, 3]: where each surviving ray leaves the last surface it
    crossed and its unit direction (lens coordinates, mm); dead rays keep their starting
    origin and direction. ``alive`` [N] bool. ``fate`` [N] int8 (``FATE_*``), ``surface`` [N] the index
    of the surface where the ray died (-1 if alive). ``path`` [S+1, N, 3] (only with
    ``record_path``): the start point and the intersection with each surface in the order
    the ray meets them; NaN from where a ray had no intersection (a ray blocked by an
    aperture keeps the point where it hit the blocking surface).
    """

    origins: np.ndarray
    directions: np.ndarray
    alive: np.ndarray
    fate: np.ndarray
    surface: np.ndarray
    path: np.ndarray | None = None
    surface_order: tuple[int, ...] = ()

    def fate_names(self) -> list[str]:
        """Human-readable fate per ray, e.g. ``"blocked at surface 5"``."""
        out = []
        for f, s in zip(self.fate.tolist(), self.surface.tolist()):
            out.append("alive" if f == FATE_ALIVE else f"{FATE_NAMES[f]} at surface {s}")
        return out


@dataclass(frozen=True)
class LensSystem:
    """A rotationally symmetric lens: surfaces from the scene side to the film side.

    ``nominal_f_number`` is the f-number the stop diameter in the file gives; ``with_fstop``
    scales the stop relative to it. ``notes`` records assumptions made while loading
    (e.g. which catalogue glass supplied a missing Abbe number).
    """

    surfaces: tuple[Surface, ...]
    name: str = "lens"
    source: str = ""
    path: str | None = None
    nominal_focal_length_mm: float | None = None
    nominal_f_number: float | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)

    # ---- geometry -------------------------------------------------------------------
    @cached_property
    def vertex_z_mm(self) -> np.ndarray:
        """Axial position of each surface vertex (front vertex at 0)."""
        t = np.array([s.thickness_mm for s in self.surfaces], dtype=np.float64)
        return np.concatenate([[0.0], np.cumsum(t[:-1])])

    @property
    def rear_z_mm(self) -> float:
        """Axial position of the last (film-side) surface vertex."""
        return float(self.vertex_z_mm[-1])

    @property
    def rear_semi_aperture_mm(self) -> float:
        return self.surfaces[-1].semi_aperture_mm

    @property
    def stop_index(self) -> int:
        """Index of the aperture stop; ``PrismInputError`` if the system has none."""
        for i, s in enumerate(self.surfaces):
            if s.is_stop:
                return i
        from ..errors import PrismInputError

        raise PrismInputError(f"Lens '{self.name}' has no aperture stop: mark one surface as the stop.")

    @property
    def stop_diameter_mm(self) -> float:
        return self.surfaces[self.stop_index].aperture_mm

    def medium_before(self, i: int):
        """The medium on the scene side of surface ``i``."""
        return AIR if i == 0 else self.surfaces[i - 1].medium

    def with_stop_diameter(self, diameter_mm: float) -> "LensSystem":
        """A copy whose aperture stop has the given diameter."""
        k = self.stop_index
        surfaces = list(self.surfaces)
        surfaces[k] = replace(surfaces[k], aperture_mm=float(diameter_mm))
        return replace(self, surfaces=tuple(surfaces))

    def with_fstop(self, fstop: float) -> "LensSystem":
        """A copy stopped to ``fstop``: stop diameter x nominal f-number / ``fstop``.

        Opening wider than the design only helps until the other clear apertures limit.
        """
        nominal = self.nominal_f_number
        if nominal is None:
            from .paraxial import paraxial_data

            nominal = paraxial_data(self).f_number
        return self.with_stop_diameter(self.stop_diameter_mm * nominal / float(fstop))

    # ---- tracing --------------------------------------------------------------------
    def trace(self, origins, directions, wavelength_nm, toward=TOWARD_SCENE, record_path=False) -> TraceResult:
        """Trace rays through every surface.

        ``origins``/``directions`` [N, 3] in lens coordinates (mm; directions need not be
        unit), ``wavelength_nm`` [N] or scalar: each ray refracts with every medium's index
        at its own wavelength. ``toward``: ``"scene"`` (from the film out through the rear
        element first, as a camera traces) or ``"film"`` (from the scene in through the
        front element).
        """
        if toward not in (TOWARD_FILM, TOWARD_SCENE):
            raise ValueError(f"toward must be 'film' or 'scene', not {toward!r}")
        o = np.asarray(origins, dtype=np.float64).reshape(-1, 3)
        d = np.asarray(directions, dtype=np.float64).reshape(-1, 3)
        n_rays = len(o)
        wl = np.broadcast_to(np.asarray(wavelength_nm, dtype=np.float64), (n_rays,))
        order = range(len(self.surfaces)) if toward == TOWARD_FILM else range(len(self.surfaces) - 1, -1, -1)
        out = np.empty((6, n_rays))
        out[:3] = o.T
        out[3:] = (d / np.linalg.norm(d, axis=1, keepdims=True)).T
        fate = np.zeros(n_rays, dtype=np.int8)
        where = np.full(n_rays, -1, dtype=np.int32)
        path = None
        if record_path:
            path = np.full((len(self.surfaces) + 1, n_rays, 3), np.nan)
            path[0] = o
        # Chunks small enough to stay in cache are several times faster than one big batch.
        for start in range(0, n_rays, TRACE_CHUNK):
            block = slice(start, min(start + TRACE_CHUNK, n_rays))
            self._trace_block(out[:, block], wl[block], order, toward, fate[block], where[block],
                              None if path is None else path[:, block])
        alive = fate == FATE_ALIVE
        return TraceResult(out[:3].T.copy(), out[3:].T.copy(), alive, fate, where, path, tuple(order))

    def _trace_block(self, out, wl, order, toward, fate, where, path):
        """Trace one block in place: ``out`` rows x, y, z, dx, dy, dz (one contiguous row per component)."""
        state = out.copy()
        ids = np.arange(state.shape[1])
        for step, i in enumerate(order, start=1):
            if not len(ids):
                break
            surface = self.surfaces[i]
            z0 = self.vertex_z_mm[i]
            t, hit_ok = _intersect(state, z0, surface.curvature_per_mm)
            state[:3] += t * state[3:]
            if path is not None:
                path[step, ids[hit_ok]] = state[:3, hit_ok].T
            inside = state[0] ** 2 + state[1] ** 2 <= surface.semi_aperture_mm**2
            self._kill(fate, where, ids[~hit_ok], FATE_MISSED, i)
            self._kill(fate, where, ids[hit_ok & ~inside], FATE_BLOCKED, i)
            keep = hit_ok & inside
            if not keep.all():
                ids, state = ids[keep], state[:, keep]
            if surface.is_stop:
                continue
            n1, n2 = (self.medium_before(i), surface.medium) if toward == TOWARD_FILM else (
                surface.medium, self.medium_before(i))
            if n1 is n2:
                continue
            wl_k = wl[ids]
            eta = n1.index(wl_k) / n2.index(wl_k)
            tir = _refract(state, z0, surface.curvature_per_mm, eta)
            if tir.any():
                self._kill(fate, where, ids[tir], FATE_TIR, i)
                ids, state = ids[~tir], state[:, ~tir]
        out[:, ids] = state

    @staticmethod
    def _kill(fate, where, ids, code, surface_index):
        fate[ids] = code
        where[ids] = surface_index


def _intersect(state, z_vertex, c):
    """Distance along the unit direction to the sphere cap (curvature ``c``) through the vertex.

    ``state`` rows: x, y, z, dx, dy, dz. The sphere is c|p|^2 - 2 p_z = 0 (p relative to the
    vertex), so a flat surface is the limit c = 0 without special cases. Of the two roots
    (stable quadratic formula) the nearest one in front of the ray that lies on the
    vertex's hemisphere (1 - c p_z > 0) is taken. Returns (t, ok).
    """
    x, y, z = state[0], state[1], state[2] - z_vertex
    dx, dy, dz = state[3], state[4], state[5]
    b = c * (x * dx + y * dy + z * dz) - dz
    cc = c * (x * x + y * y + z * z) - 2.0 * z
    disc = b * b - c * cc
    real = disc >= 0.0
    q = -(b + np.copysign(np.sqrt(np.where(real, disc, 0.0)), b))
    with np.errstate(divide="ignore", invalid="ignore"):
        near = np.where(q != 0.0, cc / q, np.inf)
        far = q / c if c != 0.0 else np.full_like(q, np.inf)
        t = np.full_like(q, np.inf)
        for root in (near, far):
            valid = real & (root > 0.0) & np.isfinite(root) & (1.0 - c * (z + root * dz) > 0.0)
            t = np.where(valid & (root < t), root, t)
    ok = np.isfinite(t)
    return np.where(ok, t, 0.0), ok


def _refract(state, z_vertex, c, eta):
    """Refract the directions in ``state`` (in place) at its points on the sphere of curvature ``c``.

    ``eta`` = n_incident / n_transmitted per ray. Returns the mask of rays that are
    totally internally reflected (their direction is left unchanged).
    """
    nx, ny, nz = c * state[0], c * state[1], c * (state[2] - z_vertex) - 1.0
    inv = 1.0 / np.sqrt(nx * nx + ny * ny + nz * nz)
    nx, ny, nz = nx * inv, ny * inv, nz * inv
    dx, dy, dz = state[3], state[4], state[5]
    cos_i = -(nx * dx + ny * dy + nz * dz)
    sign = np.where(cos_i < 0.0, -1.0, 1.0)  # orient the normal against the ray
    cos_i = cos_i * sign
    k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    tir = k < 0.0
    g = (eta * cos_i - np.sqrt(np.where(tir, 0.0, k))) * sign
    new = np.stack([eta * dx + g * nx, eta * dy + g * ny, eta * dz + g * nz])
    new *= 1.0 / np.sqrt((new * new).sum(axis=0))
    state[3:] = np.where(tir, state[3:], new)
    return tir
