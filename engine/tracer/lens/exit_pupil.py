"""Where on the rear element rays from a film point can get through: exit-pupil bounds.

For film points on the +x axis at radii spanning the film, a dense grid of rays toward the
plane of the rear vertex is traced out through the lens; the surviving rays' crossing
points give an axis-aligned box per radial bin. Because the lens is rotationally
symmetric, a film point at angle phi uses its bin's box rotated by phi. Sampling the box
instead of the whole rear element wastes few rays, and the radiometric weight keeps
vignetting physical (the method of pbrt-v3's RealisticCamera; this is our own code).
"""

from __future__ import annotations

import warnings

import numpy as np

from .media import D_LINE_NM
from .system import TOWARD_SCENE

RADIAL_BINS = 64
COARSE_GRID = 40
FINE_GRID = 32
# The pupil edge moves a little with wavelength; bound it over the visible range.
BOUND_WAVELENGTHS_NM = (380.0, 780.0)


class ExitPupilBounds:
    """Per-radial-bin boxes (x0, x1, y0, y1) on the rear vertex plane, for film points on +x.

    ``film_z_mm``: film plane (lens coordinates); ``film_radius_mm``: the largest film radius
    that will be sampled (half the film diagonal). ``full`` = True skips the search and
    uses the rear element's whole bounding square for every bin.
    """

    def __init__(self, system, film_z_mm, film_radius_mm, bins=RADIAL_BINS, full=False):
        self.system = system
        self.film_z_mm = float(film_z_mm)
        self.rear_z_mm = system.rear_z_mm
        self.film_radius_mm = float(film_radius_mm)
        self.bin_width_mm = max(self.film_radius_mm, 1e-9) / bins
        self.search_half_mm = rear_search_half_width_mm(system, self.film_z_mm, self.film_radius_mm)
        half = self.search_half_mm
        square = np.array([-half, half, -half, half])
        if full:
            self.boxes = np.tile(square, (bins, 1))
        else:
            self.boxes = self._search(square, bins)

    # ---- construction -------------------------------------------------------------------
    def _passing_boxes(self, radii, boxes, grid, wavelengths_nm):
        """For each film radius (on +x) and search box [M, 4], the box of the grid points that pass.

        Returns [M, 4] boxes (NaN rows where nothing passes) and the grid cell sizes [M, 2].
        """
        m = len(radii)
        u = (np.arange(grid) + 0.5) / grid
        gx, gy = (g.ravel() for g in np.meshgrid(u, u))
        px = boxes[:, 0:1] + gx[None, :] * (boxes[:, 1:2] - boxes[:, 0:1])
        py = boxes[:, 2:3] + gy[None, :] * (boxes[:, 3:4] - boxes[:, 2:3])
        n = px.size
        film = np.zeros((n, 3))
        film[:, 0] = np.repeat(radii, grid * grid)
        film[:, 2] = self.film_z_mm
        target = np.column_stack([px.ravel(), py.ravel(), np.full(n, self.rear_z_mm)])
        passed = np.zeros(n, dtype=bool)
        for wavelength_nm in wavelengths_nm:
            passed |= self.system.trace(film, target - film, wavelength_nm, toward=TOWARD_SCENE).alive
        passed = passed.reshape(m, -1)
        out = np.column_stack([
            np.where(passed, px, np.inf).min(axis=1), np.where(passed, px, -np.inf).max(axis=1),
            np.where(passed, py, np.inf).min(axis=1), np.where(passed, py, -np.inf).max(axis=1),
        ])
        out[~passed.any(axis=1)] = np.nan
        cells = np.column_stack([(boxes[:, 1] - boxes[:, 0]) / grid, (boxes[:, 3] - boxes[:, 2]) / grid])
        return out, cells

    def _search(self, square, bins):
        """Coarse boxes at the bin edges, then a fine search per bin at its edges and middle."""
        edges = np.arange(bins + 1) * self.bin_width_mm
        coarse, cell = self._passing_boxes(edges, np.tile(square, (bins + 1, 1)), COARSE_GRID, (D_LINE_NM,))
        # A passing region's extreme lies within one grid cell of a passing grid point;
        # grow by 2 coarse cells to also cover the pupil's drift across the bin and with
        # wavelength, then clip to the rear element.
        grown = coarse + 2.0 * np.column_stack([-cell[:, 0], cell[:, 0], -cell[:, 1], cell[:, 1]])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            search = np.column_stack([
                np.fmin(grown[:-1, 0], grown[1:, 0]), np.fmax(grown[:-1, 1], grown[1:, 1]),
                np.fmin(grown[:-1, 2], grown[1:, 2]), np.fmax(grown[:-1, 3], grown[1:, 3]),
            ])
        search[:, [0, 2]] = np.maximum(search[:, [0, 2]], square[[0, 2]])
        search[:, [1, 3]] = np.minimum(search[:, [1, 3]], square[[1, 3]])
        found = np.isfinite(search).all(axis=1)
        boxes = np.zeros((bins, 4))  # empty box: nothing passes in this bin
        if not found.any():
            return boxes
        radii = np.column_stack([edges[:-1], 0.5 * (edges[:-1] + edges[1:]), edges[1:]])[found].ravel()
        fine, fine_cell = self._passing_boxes(radii, np.repeat(search[found], 3, axis=0), FINE_GRID,
                                              BOUND_WAVELENGTHS_NM)
        fine += np.column_stack([-fine_cell[:, 0], fine_cell[:, 0], -fine_cell[:, 1], fine_cell[:, 1]])
        per_bin = fine.reshape(-1, 3, 4)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            union = np.column_stack([
                np.nanmin(per_bin[:, :, 0], axis=1), np.nanmax(per_bin[:, :, 1], axis=1),
                np.nanmin(per_bin[:, :, 2], axis=1), np.nanmax(per_bin[:, :, 3], axis=1),
            ])
        union[~np.isfinite(union).all(axis=1)] = 0.0
        boxes[found] = union
        return boxes

    # ---- use ----------------------------------------------------------------------------
    def box_for(self, film_xy_mm):
        """Box [N, 4] of the radial bin of each film point (before rotation)."""
        r = np.hypot(film_xy_mm[:, 0], film_xy_mm[:, 1])
        k = np.minimum((r / self.bin_width_mm).astype(np.int64), len(self.boxes) - 1)
        return self.boxes[k]

    def sample(self, film_xy_mm, uv):
        """Points [N, 3] on the rear vertex plane and the sampled box area [N] (mm^2).

        ``film_xy_mm`` [N, 2] film positions, ``uv`` [N, 2] uniform in [0, 1)^2. The box of
        the film point's radial bin is rotated to the film point's azimuth.
        """
        box = self.box_for(film_xy_mm)
        bx = box[:, 0] + uv[:, 0] * (box[:, 1] - box[:, 0])
        by = box[:, 2] + uv[:, 1] * (box[:, 3] - box[:, 2])
        r = np.hypot(film_xy_mm[:, 0], film_xy_mm[:, 1])
        safe = r > 0
        cos_phi = np.where(safe, film_xy_mm[:, 0] / np.where(safe, r, 1.0), 1.0)
        sin_phi = np.where(safe, film_xy_mm[:, 1] / np.where(safe, r, 1.0), 0.0)
        points = np.column_stack([cos_phi * bx - sin_phi * by, sin_phi * bx + cos_phi * by,
                                  np.full(len(bx), self.rear_z_mm)])
        area = (box[:, 1] - box[:, 0]) * (box[:, 3] - box[:, 2])
        return points, area

    def contains(self, film_xy_mm, rear_xy_mm):
        """Whether each rear-plane point lies inside its film point's (rotated) box."""
        box = self.box_for(film_xy_mm)
        r = np.hypot(film_xy_mm[:, 0], film_xy_mm[:, 1])
        safe = r > 0
        c = np.where(safe, film_xy_mm[:, 0] / np.where(safe, r, 1.0), 1.0)
        s = np.where(safe, film_xy_mm[:, 1] / np.where(safe, r, 1.0), 0.0)
        bx = c * rear_xy_mm[:, 0] + s * rear_xy_mm[:, 1]
        by = -s * rear_xy_mm[:, 0] + c * rear_xy_mm[:, 1]
        return (bx >= box[:, 0]) & (bx <= box[:, 1]) & (by >= box[:, 2]) & (by <= box[:, 3])



def rear_search_half_width_mm(system, film_z_mm, film_radius_mm) -> float:
    """Half width of a square on the rear vertex plane that every passing ray crosses.

    A ray that meets the rear surface inside its clear aperture ``a`` can cross the vertex
    plane farther out, because the surface curves away from that plane by its sag; the
    extra reach is at most |sag(a)| times the steepest slope from the film to the aperture.
    """
    rear = system.surfaces[-1]
    a = rear.semi_aperture_mm
    sag = abs(float(rear.sag_mm(a)))
    distance = float(film_z_mm) - system.rear_z_mm - sag
    slope = (float(film_radius_mm) + a) / max(distance, 1e-6)
    return a + sag * slope * 1.05
