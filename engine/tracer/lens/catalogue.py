"""The lenses bundled with Prism, and the read-outs the Camera panel and the CLI show.

bpy-free. ``lens_readouts`` uses only paraxial optics and a small trace, so it is quick
enough for a panel (the panel caches it); the CLI adds the refined focus from
``lens_report``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import PrismInputError
from .lens_file import load_lens
from .media import C_LINE_NM, D_LINE_NM, F_LINE_NM
from .paraxial import paraxial_data, sensor_distance_for_focus
from .system import TOWARD_SCENE

LENS_DIRECTORY = Path(__file__).resolve().parents[3] / "lenses"
DEFAULT_SENSOR_WIDTH_MM = 36.0  # Blender's default sensor width


def bundled_lenses() -> list[tuple[str, str, str]]:
    """(identifier, display name, absolute path) of each bundled ``lenses/*.lens``, sorted by name.

    The identifier is the file stem (stable across versions, stored in .blend files).
    """
    entries = []
    for path in sorted(LENS_DIRECTORY.glob("*.lens")):
        try:
            name = load_lens(path).name
        except PrismInputError:
            name = f"{path.stem} (invalid file)"
        entries.append((path.stem, name, str(path)))
    return sorted(entries, key=lambda e: e[1].lower())


def bundled_lens_path(identifier: str) -> str:
    """Absolute path of the bundled lens ``identifier`` (a file stem from ``bundled_lenses``)."""
    path = LENS_DIRECTORY / f"{identifier}.lens"
    if not path.is_file():
        known = ", ".join(p.stem for p in sorted(LENS_DIRECTORY.glob("*.lens")))
        raise PrismInputError(f"No bundled lens '{identifier}': choose one of {known}.")
    return str(path)


def field_of_view_deg(system, sensor_distance_mm, sensor_width_mm=DEFAULT_SENSOR_WIDTH_MM, wavelength_nm=D_LINE_NM):
    """Full horizontal field of view through the real lens, or None when no light reaches the sensor edge.

    Rays from the film point at half the sensor width are traced out through a grid over
    the rear element; the mean direction of the bundle that gets through gives the
    half-angle (distortion included, unlike 2 atan(w / 2f)).
    """
    from .exit_pupil import rear_search_half_width_mm

    half_width = 0.5 * float(sensor_width_mm)
    film_z = system.rear_z_mm + float(sensor_distance_mm)
    reach = rear_search_half_width_mm(system, film_z, half_width)
    u = np.linspace(-reach, reach, 41)
    gx, gy = (g.ravel() for g in np.meshgrid(u, u))
    film = np.tile([half_width, 0.0, film_z], (len(gx), 1))
    target = np.column_stack([gx, gy, np.full(len(gx), system.rear_z_mm)])
    result = system.trace(film, target - film, wavelength_nm, toward=TOWARD_SCENE)
    if not result.alive.any():
        return None
    d = result.directions[result.alive].mean(axis=0)
    return 2.0 * math.degrees(math.atan2(math.hypot(d[0], d[1]), -d[2]))


def image_circle_diameter_mm(system, sensor_distance_mm, wavelength_nm=D_LINE_NM, steps=240):
    """Diameter of the film area any light reaches; inf when larger than the scan (1.5 EFL + 10 mm radius).

    Film radii are scanned in ``steps`` steps, each with a grid of rays toward the rear element.
    """
    from .exit_pupil import rear_search_half_width_mm

    max_radius_mm = 1.5 * abs(paraxial_data(system, wavelength_nm).efl_mm) + 10.0
    film_z = system.rear_z_mm + float(sensor_distance_mm)
    radii = np.linspace(0.0, max_radius_mm, steps + 1)
    reach = rear_search_half_width_mm(system, film_z, max_radius_mm)
    u = np.linspace(-reach, reach, 33)
    gx, gy = (g.ravel() for g in np.meshgrid(u, u))
    film = np.zeros((len(radii) * len(gx), 3))
    film[:, 0] = np.repeat(radii, len(gx))
    film[:, 2] = film_z
    target = np.column_stack([np.tile(gx, len(radii)), np.tile(gy, len(radii)), np.full(len(film), system.rear_z_mm)])
    alive = system.trace(film, target - film, wavelength_nm, toward=TOWARD_SCENE).alive.reshape(len(radii), -1)
    lit = np.flatnonzero(alive.any(axis=1))
    if not len(lit):
        return 0.0
    return math.inf if lit[-1] == steps else 2.0 * float(radii[lit[-1]])


def lens_readouts(path, fstop=None, focus_distance_m=None, sensor_width_mm=DEFAULT_SENSOR_WIDTH_MM) -> dict:
    """Label -> text of what a user wants to know about a lens at an f-stop and focus distance.

    ``fstop`` None keeps the file's stop; ``focus_distance_m`` (from the film) None means
    infinity. Paraxial values at the d line; the field of view is traced.
    """
    base = load_lens(path)
    system = base.with_fstop(fstop) if fstop else base
    data = paraxial_data(system)
    focus_mm = math.inf if not focus_distance_m else float(focus_distance_m) * 1000.0
    out = {"Lens": system.name, "Focal length": f"{data.efl_mm:.2f} mm"}
    out["f-number"] = f"f/{data.f_number:.2f} (entrance pupil {data.entrance_pupil_diameter_mm:.2f} mm)"
    if base.nominal_f_number and fstop and fstop < base.nominal_f_number - 1e-9:
        out["f-number"] += f", wider than the design's f/{base.nominal_f_number:g}"
    infinity = sensor_distance_for_focus(system, math.inf)
    out["Film at infinity"] = f"{infinity:.3f} mm behind the rear element"
    if math.isfinite(focus_mm):
        try:
            s = sensor_distance_for_focus(system, focus_mm)
            out["Film at focus"] = f"{s:.3f} mm ({focus_mm / 1000:.3g} m)"
        except PrismInputError as error:
            out["Film at focus"] = str(error)
    fov = field_of_view_deg(system, infinity, sensor_width_mm)
    if fov is not None:
        out["Field of view"] = f"{fov:.1f}° across {sensor_width_mm:g} mm"
    else:
        circle = image_circle_diameter_mm(system, infinity)
        out["Field of view"] = f"image circle {circle:.1f} mm, narrower than {sensor_width_mm:g} mm"
    shift = _focus_shift(system)
    out["Axial colour (F–C)"] = f"{shift * 1000:.0f} µm" if abs(shift) < 0.1 else f"{shift:.2f} mm"
    out["Length"] = f"{system.rear_z_mm:.1f} mm, {len(system.surfaces)} surfaces"
    if base.notes:
        out["Notes"] = f"{len(base.notes)} (run python -m engine.tracer.lens on the file)"
    return out


def _focus_shift(system, focus_distance_mm=math.inf):
    from .focus import focus_shift_mm

    return focus_shift_mm(system, focus_distance_mm, F_LINE_NM, C_LINE_NM)


def lens_report(path, wavelength_nm=D_LINE_NM, focus_distance_mm=None, fstop=None,
                sensor_width_mm=DEFAULT_SENSOR_WIDTH_MM) -> dict:
    """Everything the CLI prints, as JSON-ready numbers (mm, degrees, nm)."""
    from .focus import focus, focus_shift_mm

    base = load_lens(path)
    system = base.with_fstop(fstop) if fstop else base
    data = paraxial_data(system, wavelength_nm)
    at_infinity = focus(system, math.inf, wavelength_nm)
    report = {
        "file": str(path),
        "name": system.name,
        "source": system.source,
        "surfaces": len(system.surfaces),
        "nominal_focal_length_mm": base.nominal_focal_length_mm,
        "nominal_f_number": base.nominal_f_number,
        "fstop": fstop,
        "wavelength_nm": float(wavelength_nm),
        "paraxial": data.as_dict(),
        "sensor_distance_mm": {
            "infinity": at_infinity.sensor_distance_mm,
            "infinity_paraxial": at_infinity.paraxial_sensor_distance_mm,
            "infinity_rms_spot_mm": at_infinity.rms_spot_mm,
        },
        "field_of_view_deg": {
            "sensor_width_mm": float(sensor_width_mm),
            "traced": field_of_view_deg(system, at_infinity.sensor_distance_mm, sensor_width_mm, wavelength_nm),
            "paraxial": 2.0 * math.degrees(math.atan(0.5 * sensor_width_mm / data.efl_mm)),
        },
        "image_circle_diameter_mm": image_circle_diameter_mm(system, at_infinity.sensor_distance_mm, wavelength_nm),
        "focus_shift_486_656_mm": {
            "infinity_paraxial": focus_shift_mm(system, math.inf),
            "infinity_best_focus": focus_shift_mm(system, math.inf, refine=True),
        },
        "notes": list(base.notes),
    }
    if focus_distance_mm is not None:
        near = focus(system, float(focus_distance_mm), wavelength_nm)
        report["focus_distance_mm"] = float(focus_distance_mm)
        report["sensor_distance_mm"].update({
            "focus_distance": near.sensor_distance_mm,
            "focus_distance_paraxial": near.paraxial_sensor_distance_mm,
            "focus_distance_rms_spot_mm": near.rms_spot_mm,
        })
        report["focus_shift_486_656_mm"]["focus_distance_paraxial"] = focus_shift_mm(system, float(focus_distance_mm))
    return report
