"""Lens files that Python's parsers or a careless editor make hostile: deep nesting, infinite glass
numbers, a curved aperture stop, UTF-16 text. Each is one line naming the file, the line and the fix."""

from __future__ import annotations

import time

import pytest

from engine.tracer.lens.__main__ import main
from engine.tracer.lens.toml_depth import deepest_nesting

STOP = "[[surface]]\nstop = true\nthickness_mm = 5\naperture_mm = 8\n\n"
LENS = ('name = "test"\n\n' + STOP + '[[surface]]\nradius_mm = 50\nthickness_mm = 4\naperture_mm = 20\n'
        'glass = "N-BK7"\n\n[[surface]]\nradius_mm = -50\nthickness_mm = 40\naperture_mm = 20\n')
GLASS = 'glass = "N-BK7"'

CASES = {
    "arrays nested 50000 deep (under the size cap)": (
        'name = "deep"\nnotes = ' + "[" * 50000 + "]" * 50000 + "\n" + LENS.split("\n", 1)[1],
        "hostile.lens, line 2: arrays or inline tables nested 50000 deep; a lens file nests 2 deep at most "
        "([[surface]] tables, the notes list) and Prism reads up to 32: remove the extra brackets."),
    "inline tables nested 400 deep": (
        LENS + "\n[[surface]]\nradius_mm = inf\naperture_mm = 20\nnote = " + "{a = " * 400 + "1" + "}" * 400 + "\n",
        "hostile.lens, line 22: arrays or inline tables nested 400 deep; a lens file nests 2 deep at most "
        "([[surface]] tables, the notes list) and Prism reads up to 32: remove the extra brackets."),
    "vd = inf": (LENS.replace(GLASS, "nd = 1.5\nvd = inf"),
                 "hostile.lens, line 13 (surface 2, 'vd'): vd = inf is not a finite number: give the glass's Abbe "
                 "number, e.g. 64.17."),
    "nd = inf": (LENS.replace(GLASS, "nd = inf\nvd = 60"),
                 "hostile.lens, line 12 (surface 2, 'nd'): nd = inf is not a finite number: give the glass's index "
                 "at 587.56 nm, e.g. 1.5168."),
    "a radius on the aperture stop": (
        LENS.replace("stop = true\n", "stop = true\nradius_mm = 30\n"),
        "hostile.lens, line 5 (surface 1, 'radius_mm'): the aperture stop is a flat opening, so it takes no radius "
        "of curvature (got 30 mm): leave 'radius_mm' out of the stop (or write inf); its opening is 'aperture_mm', "
        "a diameter."),
}


@pytest.mark.parametrize("case", list(CASES))
def test_hostile_lens_files_get_one_line(tmp_path, capsys, bad_input, case):
    text, message = CASES[case]
    path = tmp_path / "hostile.lens"
    path.write_text(text)
    began = time.perf_counter()
    status = main([str(path)])
    err = capsys.readouterr().err
    assert time.perf_counter() - began < 5
    assert status == 2 and err.strip() == f"prism lens: error: {tmp_path}/{message}", err
    bad_input(f"lens tool: {case}", status, err.strip().replace(str(tmp_path) + "/", ""))


def test_a_utf16_lens_file_is_named_utf16(tmp_path, capsys, bad_input):
    path = tmp_path / "notepad.lens"
    path.write_bytes(LENS.encode("utf-16"))
    assert main([str(path)]) == 2
    line = capsys.readouterr().err.strip()
    assert line == (f"prism lens: error: Lens file '{path}' is UTF-16 (little-endian) text, which Prism does not "
                    "read: save it as UTF-8 (e.g. Notepad ▸ Save As ▸ Encoding UTF-8).")
    bad_input("lens tool: a lens file saved as UTF-16", 2, line.replace(str(tmp_path) + "/", ""))


def test_a_radius_of_inf_on_the_stop_still_reads(tmp_path, capsys):
    path = tmp_path / "flat_stop.lens"
    path.write_text(LENS.replace("stop = true\n", "stop = true\nradius_mm = inf\n"))
    assert main([str(path)]) == 0, capsys.readouterr().err


def test_nesting_is_counted_outside_strings_and_comments():
    text = 'a = "[[[[ \\" [[["\nb = \'{{{{\'\n# [[[[[[\nc = """\n[[[[\n"""\nd = [[1], [2, [3]]]\n'
    assert deepest_nesting(text) == (3, 7)
