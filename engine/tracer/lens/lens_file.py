"""Reading lens prescriptions: Prism's ``.lens`` (TOML) and the pbrt/CS184 ``.dat`` table.

``.dat`` (legacy): one row per surface from the scene side to the film side, whitespace
separated: curvature radius, thickness to the next surface, index n_d of the medium after
the surface, clear aperture DIAMETER (all mm). Radius 0 marks the aperture stop; an index
of 0 or 1 means air. ``#`` starts a comment. The files carry no dispersion, so each glass
keeps the file's n_d and takes V_d from the catalogue glass nearest in n_d; the loaded
system's ``notes`` say which.

``.lens`` (Prism): documented in ``lenses/README.md``.

Every problem raises ``LensFileError`` naming the file, the line (and field) and the fix.
"""

from __future__ import annotations

import math
import os
import re
from functools import lru_cache

from ..errors import LensFileError, UnknownGlassError
from ..text_encoding import utf16_advice
from . import media
from .system import LensSystem, Surface
from .toml_depth import MAX_DEPTH, deepest_nesting
from .validate import validate_surfaces, where

DAT_FIELDS = ("radius", "thickness", "index", "aperture diameter")
#: A prescription is a few kilobytes; anything far larger is not a lens file, and parsing it would take long.
MAX_FILE_BYTES = 256 * 1024
SURFACE_KEYS = {"radius_mm", "thickness_mm", "aperture_mm", "glass", "nd", "vd", "stop", "note"}
TOP_KEYS = {"format", "name", "source", "focal_length_mm", "f_number", "notes", "surface"}


class CatalogueResolver:
    """Turns glass references into media using ``engine.tracer.spectra.glass``."""

    def by_name(self, name):
        return media.catalogue_medium(name)

    def by_abbe(self, n_d, v_d):
        return media.abbe_medium(n_d, v_d)

    def by_index(self, n_d):
        return media.assumed_medium(n_d)


def load_lens(path, resolver=None) -> LensSystem:
    """Load a ``.lens`` (Prism) or any other suffix (``.dat`` table) prescription."""
    path = os.fspath(path)
    if os.path.isdir(path):
        raise LensFileError(f"Lens file '{path}' is a folder: choose a .lens or .dat file in it.")
    if not os.path.isfile(path):
        raise LensFileError(f"Lens file '{path}' does not exist: choose an existing .lens or .dat file.")
    if resolver is None:
        stat = os.stat(path)
        return _load_cached(os.path.abspath(path), stat.st_mtime_ns, stat.st_size)
    return _load(path, resolver)


@lru_cache(maxsize=32)
def _load_cached(path, _mtime_ns, _size) -> LensSystem:
    return _load(path, CatalogueResolver())


def _load(path, resolver) -> LensSystem:
    try:
        with open(path, "rb") as handle:
            data = handle.read(MAX_FILE_BYTES + 1)
        text = data.decode("utf-8")
    except OSError as exc:
        raise LensFileError(f"Lens file '{path}' cannot be read: {exc.strerror or exc}.") from exc
    except UnicodeDecodeError as exc:
        utf16 = utf16_advice(data)
        if utf16:
            raise LensFileError(f"Lens file '{path}' {utf16}.") from exc
        raise LensFileError(
            f"Lens file '{path}' is not UTF-8 text (byte {exc.start}): give a .lens or .dat text file."
        ) from exc
    if len(data) > MAX_FILE_BYTES:
        raise LensFileError(
            f"Lens file '{path}' is larger than {MAX_FILE_BYTES // 1024} KiB: a prescription is a few kilobytes, "
            "so this is not a lens file (or not one Prism reads)."
        )
    if path.lower().endswith(".lens"):
        return parse_prism_lens(text, path, resolver)
    return parse_dat(text, path, resolver)


# ---- pbrt / CS184 table -----------------------------------------------------------------
def parse_dat(text: str, path: str = "<lens>", resolver=None) -> LensSystem:
    """Parse a pbrt/CS184 ``.dat`` table (see the module docstring)."""
    resolver = resolver or CatalogueResolver()
    surfaces, notes, comments = [], [], []
    for lineno, raw in enumerate(text.splitlines(), start=1):
        body, _, comment = raw.partition("#")
        if not body.strip():
            if comment.strip() and not surfaces:
                comments.append(comment.strip().strip('"').strip())
            continue
        fields = body.split()
        if len(fields) != 4:
            raise LensFileError(
                f"{where(path, lineno)}: expected 4 columns ({', '.join(DAT_FIELDS)}), found {len(fields)}."
            )
        values = []
        for column, (name, field) in enumerate(zip(DAT_FIELDS, fields), start=1):
            try:
                value = float(field)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                raise LensFileError(
                    f"{where(path, lineno)}, column {column} ({name}): '{field}' is not a finite number."
                )
            values.append(value)
        radius, thickness, index, aperture = values
        is_stop = radius == 0.0
        if index in (0.0, 1.0):
            medium = media.AIR
        elif index < 1.0:
            raise LensFileError(
                f"{where(path, lineno)}, column 3 (index): {index:g} is not a refractive index "
                "(use 1 or 0 for air, otherwise a value above 1)."
            )
        else:
            medium, glass_name = resolver.by_index(index)
            notes.append(
                f"line {lineno}: n_d {index:g} from the file, V_d {medium.v_d:.2f} assumed from {glass_name} "
                "(the catalogue glass nearest in n_d)"
            )
        surfaces.append(Surface(math.inf if is_stop else radius, thickness, aperture, medium, is_stop, lineno))
    if not surfaces:
        raise LensFileError(f"{path}: no surface rows found (expected rows of {', '.join(DAT_FIELDS)}).")
    validate_surfaces(surfaces, path)
    name = comments[0] if comments else os.path.splitext(os.path.basename(path))[0]
    system = LensSystem(tuple(surfaces), name=name, source="; ".join(comments[1:]), path=path, notes=tuple(notes))
    return _with_paraxial_nominals(system)


def _with_paraxial_nominals(system: LensSystem) -> LensSystem:
    from dataclasses import replace

    from .paraxial import paraxial_data

    data = paraxial_data(system)
    _check_forms_an_image(system, data)
    note = f"nominal f/{data.f_number:.3g} and focal length {data.efl_mm:.4g} mm computed paraxially (d line)"
    return replace(
        system,
        nominal_focal_length_mm=system.nominal_focal_length_mm or data.efl_mm,
        nominal_f_number=system.nominal_f_number or data.f_number,
        notes=system.notes + (note,) if system.nominal_f_number is None else system.notes,
    )


def _check_forms_an_image(system: LensSystem, data) -> None:
    """A camera lens must converge and bring distant light to a focus behind its last surface."""
    if data.efl_mm <= 0:
        raise LensFileError(
            f"{system.path}: the lens diverges (focal length {data.efl_mm:.4g} mm at the d line), so it forms no "
            "image on a film. Check the signs of the radii: positive means the centre of curvature lies toward "
            "the film."
        )
    if data.bfl_mm <= 0:
        raise LensFileError(
            f"{system.path}: distant objects come to focus {-data.bfl_mm:.4g} mm inside the lens (back focal "
            f"length {data.bfl_mm:.4g} mm), where no film can go. Check the thicknesses and radii."
        )


# ---- Prism .lens (TOML) -----------------------------------------------------------------
def parse_prism_lens(text: str, path: str = "<lens>", resolver=None) -> LensSystem:
    """Parse a Prism ``.lens`` file (TOML; format in ``lenses/README.md``)."""
    import tomllib

    resolver = resolver or CatalogueResolver()
    depth, depth_line = deepest_nesting(text)
    if depth > MAX_DEPTH:
        raise LensFileError(
            f"{where(path, depth_line)}: arrays or inline tables nested {depth} deep; a lens file nests 2 deep at "
            f"most ([[surface]] tables, the notes list) and Prism reads up to {MAX_DEPTH}: remove the extra brackets."
        )
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise LensFileError(f"{path}: not valid TOML: {exc}.") from exc
    except RecursionError:  # a nesting the count above missed: still one message, not a traceback
        raise LensFileError(f"{path}: nested too deeply for Python's TOML reader: remove the extra brackets.") from None
    lines = _key_lines(text)
    for key in doc:
        if key not in TOP_KEYS:
            raise LensFileError(
                f"{where(path, lines.get((None, key)))}: unknown key '{key}' (allowed: {', '.join(sorted(TOP_KEYS))})."
            )
    rows = doc.get("surface")
    if not isinstance(rows, list) or not rows:
        raise LensFileError(f"{path}: no [[surface]] tables; list the surfaces from the scene side to the film.")
    surfaces = [_prism_surface(k, row, lines, path, resolver, len(rows)) for k, row in enumerate(rows)]
    validate_surfaces(surfaces, path)
    system = LensSystem(
        tuple(surfaces),
        name=str(doc.get("name") or os.path.splitext(os.path.basename(path))[0]),
        source=str(doc.get("source", "")),
        path=path,
        nominal_focal_length_mm=_optional_positive(doc, "focal_length_mm", lines, path),
        nominal_f_number=_optional_positive(doc, "f_number", lines, path),
        notes=tuple(str(n) for n in doc.get("notes", [])),
    )
    return _with_paraxial_nominals(system)


def _prism_surface(k, row, lines, path, resolver, count) -> Surface:
    header = lines.get((k, None))

    def at(key=None):
        return where(path, lines.get((k, key), header)) + f" (surface {k + 1}" + (f", '{key}')" if key else ")")

    for key in row:
        if key not in SURFACE_KEYS:
            raise LensFileError(f"{at(key)}: unknown key (allowed: {', '.join(sorted(SURFACE_KEYS))}).")

    def number(key, default=None):
        if key not in row:
            if default is None:
                raise LensFileError(f"{at()}: missing '{key}'.")
            return default
        value = row[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value):
            raise LensFileError(f"{at(key)}: {value!r} is not a number.")
        return float(value)

    is_stop = row.get("stop", False)
    if not isinstance(is_stop, bool):
        raise LensFileError(f"{at('stop')}: must be true or false.")
    radius = number("radius_mm", math.inf if is_stop else None)
    if is_stop and math.isfinite(radius):
        raise LensFileError(
            f"{at('radius_mm')}: the aperture stop is a flat opening, so it takes no radius of curvature "
            f"(got {radius:g} mm): leave 'radius_mm' out of the stop (or write inf); its opening is 'aperture_mm', "
            "a diameter."
        )
    if radius == 0.0:
        raise LensFileError(f"{at('radius_mm')}: radius 0 is not a surface; use inf for a flat surface.")
    thickness = number("thickness_mm", 0.0 if k == count - 1 else None)
    aperture = number("aperture_mm")
    if not math.isfinite(thickness) or not math.isfinite(aperture):
        raise LensFileError(f"{at()}: thickness and aperture must be finite.")
    medium = _prism_medium(row, at, resolver)
    if is_stop and not medium.is_air:
        raise LensFileError(f"{at('glass')}: the aperture stop must be followed by air.")
    return Surface(radius, thickness, aperture, medium, is_stop, lines.get((k, "radius_mm"), header))


def _prism_medium(row, at, resolver):
    glass = row.get("glass")
    has_abbe = "nd" in row or "vd" in row
    if glass is not None and has_abbe:
        raise LensFileError(f"{at('glass')}: give either a glass name or nd and vd, not both.")
    if has_abbe:
        if "nd" not in row or "vd" not in row:
            raise LensFileError(f"{at()}: give both 'nd' and 'vd' (or a catalogue 'glass' name).")
        n_d, v_d = row["nd"], row["vd"]
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (n_d, v_d)):
            raise LensFileError(f"{at('nd')}: nd and vd must be numbers.")
        for key, value in (("nd", n_d), ("vd", v_d)):
            if not math.isfinite(value):
                raise LensFileError(f"{at(key)}: {key} = {value} is not a finite number: give the glass's "
                                    f"{'index at 587.56 nm, e.g. 1.5168' if key == 'nd' else 'Abbe number, e.g. 64.17'}.")
        if not (n_d > 1.0 and v_d > 0.0):
            raise LensFileError(f"{at('nd')}: need nd > 1 and vd > 0 (got {n_d}, {v_d}).")
        return resolver.by_abbe(float(n_d), float(v_d))
    if glass is None or (isinstance(glass, str) and glass.strip().lower() == "air"):
        return media.AIR
    if not isinstance(glass, str):
        raise LensFileError(f"{at('glass')}: must be a catalogue glass name or \"air\".")
    try:
        return resolver.by_name(glass)
    except UnknownGlassError as exc:
        raise LensFileError(f"{at('glass')}: {_unknown_glass_message(glass)}") from exc


def _unknown_glass_message(name) -> str:
    from ..spectra.glass import glass_names

    return f"unknown glass '{name}'. Known glasses: {', '.join(glass_names())}; or give 'nd' and 'vd'."


def _optional_positive(doc, key, lines, path):
    if key not in doc:
        return None
    value = doc[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
        raise LensFileError(f"{where(path, lines.get((None, key)))}: '{key}' must be a positive number.")
    return float(value)


_HEADER = re.compile(r"^\s*\[\[\s*surface\s*\]\]")
_KEY = re.compile(r"^\s*([A-Za-z0-9_\-]+)\s*=")


def _key_lines(text: str) -> dict:
    """Map (surface index or None for top level, key or None for the header) -> line number."""
    lines, current = {}, None
    for lineno, raw in enumerate(text.splitlines(), start=1):
        if _HEADER.match(raw):
            current = 0 if current is None else current + 1
            lines[(current, None)] = lineno
            continue
        match = _KEY.match(raw)
        if match:
            lines.setdefault((current, match.group(1)), lineno)
    return lines
