"""A lens system (spherical surfaces, an aperture stop) and float64 ray tracing through it.

Lens coordinates, millimetres: the optical axis is +z, pointing from the scene toward the
film; the first (front) surface vertex is at z = 0 and each surface's ``thickness_mm`` is
the axial distance to the next one. A positive ``radius_mm`` puts the centre of curvature
on the film side of the vertex (a front surface that bulges toward the scene); ``inf`` is a
flat surface. ``medium`` of a surface fills the space after it (toward the film); the
scene side of the first surface and the film side of the last are air.

``LensSystem.trace`` runs the one compiled lens tracer (``trace_kernel.py``) over a batch: a
ray that misses a surface, falls outside its clear aperture (or the stop), or is totally
internally reflected dies and its fate is recorded.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from .media import AIR
from .ray_fate import FATE_ALIVE, FATE_NAMES

# Arrays handed to the lens kernels are C-contiguous and writable (np.require copies
# otherwise): a read-only or strided input would compile and cache another specialisation.
KERNEL_ARRAY = ("C", "W")

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
    @cached_property
    def tables(self):
        """This system as the flat arrays (``tables.LensTables``) the compiled lens kernels read."""
        from .tables import lens_tables

        return lens_tables(self)

    def trace(self, origins, directions, wavelength_nm, toward=TOWARD_SCENE, record_path=False) -> TraceResult:
        """Trace rays through every surface (one compiled loop over ``trace_kernel.trace_ray``).

        ``origins``/``directions`` [N, 3] in lens coordinates (mm; directions need not be
        unit), ``wavelength_nm`` [N] or scalar: each ray refracts with every medium's index
        at its own wavelength. ``toward``: ``"scene"`` (from the film out through the rear
        element first, as a camera traces) or ``"film"`` (from the scene in through the
        front element).
        """
        if toward not in (TOWARD_FILM, TOWARD_SCENE):
            raise ValueError(f"toward must be 'film' or 'scene', not {toward!r}")
        from .trace_kernel import trace_rays  # numba loads when a lens is first traced, not when one is read

        o = np.require(np.reshape(origins, (-1, 3)), np.float64, KERNEL_ARRAY)
        d = np.require(np.reshape(directions, (-1, 3)), np.float64, KERNEL_ARRAY)
        n_rays = len(o)
        wl = np.require(np.broadcast_to(wavelength_nm, (n_rays,)), np.float64, KERNEL_ARRAY)
        count = len(self.surfaces)
        out_origins, out_directions = np.empty((n_rays, 3)), np.empty((n_rays, 3))
        fate = np.empty(n_rays, dtype=np.int8)
        where = np.empty(n_rays, dtype=np.int32)
        paths = np.full((n_rays, count + 1, 3), np.nan) if record_path else None
        trace_rays(self.tables, o, d, wl, toward == TOWARD_FILM, out_origins, out_directions, fate, where, paths)
        order = range(count) if toward == TOWARD_FILM else range(count - 1, -1, -1)
        path = None if paths is None else paths.transpose(1, 0, 2)
        return TraceResult(out_origins, out_directions, fate == FATE_ALIVE, fate, where, path, tuple(order))
