"""Where on the rear element rays from a film point can get through: exit-pupil bounds.

For film points on the +x axis at radii spanning the film, grids of rays toward the plane
of the rear vertex are traced out through the lens (coarse over the whole reachable
square, then finer inside what passed, at the ends of the visible range); the surviving
rays' crossing points give, per radial bin, an axis-aligned box and an ellipse that hold
them (grown by one grid cell), and the smaller of the two is sampled uniformly. Because
the lens is rotationally symmetric, a film point at azimuth phi uses its bin's shape
rotated by phi (``pupil_sampling.py`` draws the samples). Sampling that shape instead of
the whole rear element wastes few rays; the radiometric weight (area / distance^2 x cos^4)
keeps vignetting physical (the method of pbrt-v3's RealisticCamera, extended with the
ellipse; this is our own code)."""

from __future__ import annotations

import warnings
from functools import cached_property

import numpy as np

from .media import D_LINE_NM
from .system import KERNEL_ARRAY, TOWARD_SCENE

RADIAL_BINS = 64
COARSE_GRID = 40
MAX_COARSE_GRID = 200
COARSE_CELLS_PER_PUPIL = 6
COARSE_BIN_STEP = 4
MIDDLE_GRID = 24
FINE_GRID = 40
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
            self.ellipses, self.use_ellipse = np.zeros((bins, 4)), np.zeros(bins, dtype=bool)
        else:
            self.boxes, self.ellipses, self.use_ellipse = self._search(square, bins)

    # ---- construction -------------------------------------------------------------------
    def _passing_boxes(self, radii, boxes, grid, wavelengths_nm):
        """For each film radius (on +x) and search box [M, 4], the box of the grid points that pass.

        Returns [M, 4] boxes (NaN rows where nothing passes), the grid cell sizes [M, 2] and
        (passed, x, y) [M, grid^2] of the grid points.
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
        for wavelength_nm in wavelengths_nm:  # a ray that passed at one wavelength needs no other
            todo = np.flatnonzero(~passed)
            passed[todo] = self.system.trace(film[todo], target[todo] - film[todo], wavelength_nm,
                                             toward=TOWARD_SCENE).alive
        passed = passed.reshape(m, -1)
        out = np.column_stack([
            np.where(passed, px, np.inf).min(axis=1), np.where(passed, px, -np.inf).max(axis=1),
            np.where(passed, py, np.inf).min(axis=1), np.where(passed, py, -np.inf).max(axis=1),
        ])
        out[~passed.any(axis=1)] = np.nan
        cells = np.column_stack([(boxes[:, 1] - boxes[:, 0]) / grid, (boxes[:, 3] - boxes[:, 2]) / grid])
        return out, cells, (passed, px, py)

    def _coarse_grid(self, half_width_mm):
        """Coarse grid size: fine enough that the paraxial exit pupil, projected onto the
        rear vertex plane, spans several cells even when stopped far down."""
        from .paraxial import paraxial_data

        data = paraxial_data(self.system)
        to_pupil = self.film_z_mm - data.exit_pupil_z_mm
        to_rear = self.film_z_mm - self.rear_z_mm
        projected = data.exit_pupil_diameter_mm * abs(to_rear / to_pupil) if abs(to_pupil) > 1e-9 else np.inf
        wanted = 2.0 * half_width_mm / max(projected / COARSE_CELLS_PER_PUPIL, 1e-9)
        return int(np.clip(np.ceil(wanted), COARSE_GRID, MAX_COARSE_GRID))

    def _search(self, square, bins):
        """Coarse boxes every few bins, then a fine search per bin at its edges and middle."""
        edges = np.arange(bins + 1) * self.bin_width_mm
        step = COARSE_BIN_STEP if bins % COARSE_BIN_STEP == 0 else 1
        coarse_radii = edges[::step]
        grid = self._coarse_grid(square[1])
        coarse, cell, _ = self._passing_boxes(coarse_radii, np.tile(square, (len(coarse_radii), 1)), grid,
                                              (D_LINE_NM,))
        # A passing region's extreme lies within one grid cell of a passing grid point;
        # grow by 2 coarse cells to also cover the pupil's drift across the bins and with
        # wavelength; each bin searches the union of the boxes at the coarse radii around
        # it, clipped to the search square.
        grown = coarse + 2.0 * np.column_stack([-cell[:, 0], cell[:, 0], -cell[:, 1], cell[:, 1]])
        # The coarse radius before the bracketing pair is included too: at the edge of the
        # image circle the pupil shrinks to a sliver the coarse grid can miss.
        lo = np.arange(bins) // step
        around = grown[np.stack([np.maximum(lo - 1, 0), lo, lo + 1])]  # [3, bins, 4]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            search = np.column_stack([
                np.nanmin(around[:, :, 0], axis=0), np.nanmax(around[:, :, 1], axis=0),
                np.nanmin(around[:, :, 2], axis=0), np.nanmax(around[:, :, 3], axis=0),
            ])
        search[:, [0, 2]] = np.maximum(search[:, [0, 2]], square[[0, 2]])
        search[:, [1, 3]] = np.minimum(search[:, [1, 3]], square[[1, 3]])
        found = np.isfinite(search).all(axis=1)
        boxes = np.zeros((bins, 4))  # empty box: nothing passes in this bin
        ellipses = np.zeros((bins, 4))
        use_ellipse = np.zeros(bins, dtype=bool)
        if not found.any():
            return boxes, ellipses, use_ellipse
        radii = np.column_stack([edges[:-1], 0.5 * (edges[:-1] + edges[1:]), edges[1:]])[found].ravel()
        # A medium grid narrows each bin's search box to its pupil, so the
        # fine grid's cells (and the safety margin of one cell) are small.
        middle, middle_cell, _ = self._passing_boxes(radii, np.repeat(search[found], 3, axis=0), MIDDLE_GRID,
                                                     BOUND_WAVELENGTHS_NM)
        middle += 1.5 * np.column_stack([-middle_cell[:, 0], middle_cell[:, 0], -middle_cell[:, 1], middle_cell[:, 1]])
        middle = middle.reshape(-1, 3, 4)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            narrow = np.column_stack([
                np.nanmin(middle[:, :, 0], axis=1), np.nanmax(middle[:, :, 1], axis=1),
                np.nanmin(middle[:, :, 2], axis=1), np.nanmax(middle[:, :, 3], axis=1),
            ])
        narrow[:, [0, 2]] = np.maximum(narrow[:, [0, 2]], square[[0, 2]])
        narrow[:, [1, 3]] = np.minimum(narrow[:, [1, 3]], square[[1, 3]])
        missed = ~np.isfinite(narrow).all(axis=1)
        narrow[missed] = search[found][missed]
        fine, fine_cell, (passed, px, py) = self._passing_boxes(
            radii, np.repeat(narrow, 3, axis=0), FINE_GRID, BOUND_WAVELENGTHS_NM)
        fine += np.column_stack([-fine_cell[:, 0], fine_cell[:, 0], -fine_cell[:, 1], fine_cell[:, 1]])
        per_bin = fine.reshape(-1, 3, 4)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            union = np.column_stack([
                np.nanmin(per_bin[:, :, 0], axis=1), np.nanmax(per_bin[:, :, 1], axis=1),
                np.nanmin(per_bin[:, :, 2], axis=1), np.nanmax(per_bin[:, :, 3], axis=1),
            ])
        empty = ~np.isfinite(union).all(axis=1)
        union[empty] = 0.0
        boxes[found] = union
        # An ellipse with the box's centre and aspect, scaled to hold every passing point
        # and grown by one grid cell, wastes far less than the box on round pupils.
        centre_x, centre_y = 0.5 * (union[:, 0] + union[:, 1]), 0.5 * (union[:, 2] + union[:, 3])
        half_x = np.maximum(0.5 * (union[:, 1] - union[:, 0]), 1e-12)
        half_y = np.maximum(0.5 * (union[:, 3] - union[:, 2]), 1e-12)
        nb = len(union)
        rho2 = (((px.reshape(nb, -1) - centre_x[:, None]) / half_x[:, None]) ** 2
                + ((py.reshape(nb, -1) - centre_y[:, None]) / half_y[:, None]) ** 2)
        scale = np.sqrt(np.where(passed.reshape(nb, -1), rho2, 0.0).max(axis=1))
        cell = fine_cell.reshape(nb, 3, 2).max(axis=1)
        margin = cell.max(axis=1)
        semi_x, semi_y = scale * half_x + margin, scale * half_y + margin
        ellipses[found] = np.column_stack([centre_x, centre_y, semi_x, semi_y])
        use_ellipse[found] = (np.pi * semi_x * semi_y < 4.0 * half_x * half_y) & ~empty
        return boxes, ellipses, use_ellipse

    # ---- use ----------------------------------------------------------------------------
    def bin_of(self, film_xy_mm):
        """Radial bin index [N] of each film point."""
        r = np.hypot(film_xy_mm[:, 0], film_xy_mm[:, 1])
        return np.minimum((r / self.bin_width_mm).astype(np.int64), len(self.boxes) - 1)

    @staticmethod
    def _azimuth(film_xy_mm):
        r = np.hypot(film_xy_mm[:, 0], film_xy_mm[:, 1])
        safe = r > 0
        cos_phi = np.where(safe, film_xy_mm[:, 0] / np.where(safe, r, 1.0), 1.0)
        sin_phi = np.where(safe, film_xy_mm[:, 1] / np.where(safe, r, 1.0), 0.0)
        return cos_phi, sin_phi

    @cached_property
    def tables(self):
        """The bins as ``pupil_sampling.PupilTables`` for the compiled camera."""
        from .pupil_sampling import PupilTables

        return PupilTables(float(self.rear_z_mm), float(self.bin_width_mm), np.ascontiguousarray(self.boxes),
                           np.ascontiguousarray(self.ellipses), np.ascontiguousarray(self.use_ellipse))

    def sample(self, film_xy_mm, uv):
        """Points [N, 3] on the rear vertex plane and the area [N] (mm^2) they were drawn from.

        ``film_xy_mm`` [N, 2] film positions, ``uv`` [N, 2] uniform in [0, 1)^2. Each film
        point samples its radial bin's shape (box or ellipse, whichever is smaller)
        uniformly, rotated to the film point's azimuth (``pupil_sampling.sample_exit_pupil``).
        """
        from .pupil_sampling import sample_exit_pupil_rows

        film_xy_mm = np.require(np.reshape(film_xy_mm, (-1, 2)), np.float64, KERNEL_ARRAY)
        uv = np.require(np.reshape(uv, (-1, 2)), np.float64, KERNEL_ARRAY)
        points, area = np.empty((len(film_xy_mm), 3)), np.empty(len(film_xy_mm))
        sample_exit_pupil_rows(self.tables, film_xy_mm, uv, points, area)
        return points, area

    def contains(self, film_xy_mm, rear_xy_mm):
        """Whether each rear-plane point lies inside its film point's (rotated) sampling shape."""
        k = self.bin_of(film_xy_mm)
        box, ellipse, round_ = self.boxes[k], self.ellipses[k], self.use_ellipse[k]
        c, s = self._azimuth(film_xy_mm)
        bx = c * rear_xy_mm[:, 0] + s * rear_xy_mm[:, 1]
        by = -s * rear_xy_mm[:, 0] + c * rear_xy_mm[:, 1]
        in_box = (bx >= box[:, 0]) & (bx <= box[:, 1]) & (by >= box[:, 2]) & (by <= box[:, 3])
        with np.errstate(divide="ignore", invalid="ignore"):
            in_ellipse = ((bx - ellipse[:, 0]) / ellipse[:, 2]) ** 2 + ((by - ellipse[:, 1]) / ellipse[:, 3]) ** 2 <= 1.0
        return np.where(round_, in_ellipse, in_box)


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
