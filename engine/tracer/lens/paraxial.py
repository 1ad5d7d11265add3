"""First-order (paraxial) optics of a lens system by 2x2 ray-transfer matrices.

State vector (y, n u): height in mm and reduced angle. A surface of curvature c between
indices n and n' refracts with [[1, 0], [-(n' - n) c, 1]]; a gap of thickness t in index n
transfers with [[1, t / n], [0, 1]]. Object and image space are air. Positions are lens
coordinates (mm, front vertex at z = 0, +z toward the film).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..errors import PrismInputError
from .media import D_LINE_NM


@dataclass(frozen=True)
class ParaxialData:
    """First-order properties at one wavelength (mm; z in lens coordinates).

    ``bfl_mm``: last vertex to the rear focal point; ``ffl_mm``: front focal point
    position relative to the front vertex (negative = in front of it).
    """

    wavelength_nm: float
    efl_mm: float
    bfl_mm: float
    ffl_mm: float
    front_principal_z_mm: float
    back_principal_z_mm: float
    entrance_pupil_z_mm: float
    entrance_pupil_diameter_mm: float
    exit_pupil_z_mm: float
    exit_pupil_diameter_mm: float
    f_number: float
    length_mm: float

    def as_dict(self) -> dict:
        return asdict(self)


def _refraction(surface, n1, n2):
    return np.array([[1.0, 0.0], [-(n2 - n1) * surface.curvature_per_mm, 1.0]])


def _transfer(t_mm, n):
    return np.array([[1.0, t_mm / n], [0.0, 1.0]])


def _indices(system, wavelength_nm):
    """Index after each surface (and 1 before the first) at one wavelength."""
    wl = np.array([float(wavelength_nm)])
    return [1.0] + [float(s.medium.index(wl)[0]) for s in system.surfaces]


def system_matrix(system, wavelength_nm=D_LINE_NM, first=0, last=None, end_at_vertex=True):
    """Matrix from just before surface ``first`` to just after surface ``last`` (inclusive).

    With ``end_at_vertex`` False the gap after ``last`` is included too.
    """
    last = len(system.surfaces) - 1 if last is None else last
    n = _indices(system, wavelength_nm)
    m = np.eye(2)
    for i in range(first, last + 1):
        s = system.surfaces[i]
        m = _refraction(s, n[i], n[i + 1]) @ m
        if i < last or not end_at_vertex:
            m = _transfer(s.thickness_mm, n[i + 1]) @ m
    return m


def paraxial_data(system, wavelength_nm=D_LINE_NM) -> ParaxialData:
    """EFL, BFL, principal planes, pupils and f-number at ``wavelength_nm``."""
    (a, b), (c, d) = system_matrix(system, wavelength_nm)
    if abs(c) < 1e-15:
        raise PrismInputError(f"Lens '{system.name}' is afocal (no focal length): it cannot form an image.")
    length = system.rear_z_mm
    efl = -1.0 / c
    bfl = -a / c
    ffl = d / c
    back_principal = length + bfl - efl
    front_principal = ffl + efl

    k = system.stop_index
    stop_z = float(system.vertex_z_mm[k])
    stop_d = system.stop_diameter_mm
    if k == 0:
        ep_z, ep_d = stop_z, stop_d
    else:
        # Matrix from the front vertex plane to the stop plane; the entrance pupil is the
        # object-space plane conjugate to the stop.
        front = _transfer(system.surfaces[k - 1].thickness_mm, 1.0) @ system_matrix(system, wavelength_nm, 0, k - 1)
        ep_z = front[0, 1] / front[0, 0]
        ep_d = stop_d / abs(front[0, 0])
    if k == len(system.surfaces) - 1:
        xp_z, xp_d = stop_z, stop_d
    else:
        back = system_matrix(system, wavelength_nm, k + 1, None) @ _transfer(system.surfaces[k].thickness_mm, 1.0)
        shift = -back[0, 1] / back[1, 1]
        xp_z = length + shift
        xp_d = stop_d * abs(back[0, 0] + shift * back[1, 0])
    return ParaxialData(
        float(wavelength_nm), efl, bfl, ffl, front_principal, back_principal,
        float(ep_z), float(ep_d), float(xp_z), float(xp_d), efl / ep_d, length,
    )


def image_distance_mm(system, object_z_mm, wavelength_nm=D_LINE_NM) -> float:
    """Paraxial image of an axial point at ``object_z_mm`` (lens coords, < 0), measured from the last vertex.

    ``object_z_mm = -inf`` gives the back focal length.
    """
    (a, b), (c, d) = system_matrix(system, wavelength_nm)
    if not np.isfinite(object_z_mm):
        return -a / c
    u = -float(object_z_mm)  # object distance in front of the first vertex
    return -(a * u + b) / (c * u + d)


def sensor_distance_for_focus(system, focus_distance_mm, wavelength_nm=D_LINE_NM) -> float:
    """Paraxial last-vertex-to-film distance that focuses an object ``focus_distance_mm`` from the FILM.

    The object distance is measured from the film plane (as a photographer's focus scale and
    Blender's focus distance are), so moving the film moves the object: with ``u`` =
    object-to-front-vertex distance = D - L - s, the conjugate condition
    s (C u + D') + A u + B = 0 is a quadratic in s. ``inf`` gives the back focal length.
    """
    (a, b), (c, d) = system_matrix(system, wavelength_nm)
    if not np.isfinite(focus_distance_mm):
        return -a / c
    length = system.rear_z_mm
    big = float(focus_distance_mm) - length
    # -c s^2 + s (c big + d - a) + a big + b = 0
    coeffs = [-c, c * big + d - a, a * big + b]
    roots = np.roots(coeffs)
    real = roots[np.isreal(roots)].real
    bfl = -a / c
    real = real[(real > 0) & (real < big)]
    if not len(real):
        raise PrismInputError(
            f"Lens '{system.name}' cannot focus at {focus_distance_mm / 1000:.3g} m from the film: "
            "that is closer than it can focus. Increase the focus distance."
        )
    return float(real[np.argmin(np.abs(real - bfl))])
