"""``python -m engine.tracer.lens`` on hostile files and arguments: bounded work, one line naming the
file or option and the fix, exit status 2, never a traceback."""

from __future__ import annotations

import pytest

from engine.tracer.lens.__main__ import main
from engine.tracer.lens.catalogue import LENS_DIRECTORY

LENS = str(LENS_DIRECTORY / "double_gauss_50mm.lens")


def _surface(radius, thickness, aperture, extra=""):
    return f"[[surface]]\nradius_mm = {radius}\nthickness_mm = {thickness}\naperture_mm = {aperture}\n{extra}\n"


def _lens(*surfaces):
    stop = '[[surface]]\nstop = true\nthickness_mm = 5\naperture_mm = 8\n\n'
    return 'name = "test"\n\n' + stop + "".join(surfaces) + _surface("inf", 0, 20)


CONVERGING = _surface(50, 4, 20, 'glass = "N-BK7"') + _surface(-50, 40, 20)
FILE_CASES = {
    "a diverging lens": (
        _lens(_surface(-50, 3, 20, 'glass = "N-BK7"'), _surface(50, 40, 20)),
        "the lens diverges (focal length -47.89 mm at the d line), so it forms no image on a film",
    ),
    "a lens that focuses inside itself": (
        _lens(_surface(10, 30, 12, 'glass = "N-SF11"'), _surface(-10, 1, 12)),
        "distant objects come to focus",
    ),
    "a valid but enormous prescription (1004 surfaces)": (
        _lens(*[_surface("inf", 0.01, 20, 'glass = "N-BK7"') + _surface("inf", 0.01, 20)] * 500, CONVERGING),
        "1004 surfaces; Prism traces lenses of up to 100 (real lenses have about 50 at most)",
    ),
    "a 300 KiB file": ("# padding\n" * 30000 + _lens(CONVERGING), "is larger than 256 KiB: a prescription is a few kilobytes"),
    "a thickness of 1e9 mm": (_lens(_surface(50, 1e9, 20, 'glass = "N-BK7"'), _surface(-50, 40, 20)),
                              "thickness 1e+09 mm is more than 100000 mm (100 m): lens files are in millimetres"),
    "a radius of 1e300 mm": (_lens(_surface(1e300, 4, 20, 'glass = "N-BK7"'), _surface(-50, 40, 20)),
                             "radius 1e+300 mm is flat for any aperture: write inf instead"),
}


@pytest.mark.parametrize("case", list(FILE_CASES))
def test_hostile_lens_files_are_refused_naming_the_file(tmp_path, capsys, bad_input, case):
    text, message = FILE_CASES[case]
    path = tmp_path / "hostile.lens"
    path.write_text(text)
    status = main([str(path)])
    captured = capsys.readouterr()
    line = captured.err.strip()
    assert status == 2 and captured.out == ""
    assert line.startswith(f"prism lens: error: {path}") or line.startswith(f"prism lens: error: Lens file '{path}'")
    assert message in line and "Traceback" not in captured.err and len(captured.err.splitlines()) == 1
    bad_input(f"lens tool: {case}", status, line.replace(str(tmp_path) + "/", ""))


def test_files_that_are_no_lens_files(tmp_path, capsys, bad_input):
    binary = tmp_path / "image.lens"
    binary.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff")
    for description, path, message in [
        ("a binary file", binary, "is not UTF-8 text (byte 0): give a .lens or .dat text file."),
        ("a folder", tmp_path, "is a folder: choose a .lens or .dat file in it."),
    ]:
        assert main([str(path)]) == 2
        line = capsys.readouterr().err.strip()
        assert message in line
        bad_input(f"lens tool: {description}", 2, line.replace(str(tmp_path), "…"))


ARGUMENT_CASES = [
    (["--wavelength", "nan"], "argument --wavelength: the wavelength must be between 360 and 830 nm (got nan)"),
    (["--wavelength", "-5"], "the wavelength must be between 360 and 830 nm (got -5), the range Prism renders"),
    (["--wavelength", "blue"], "argument --wavelength: the wavelength must be a number (got 'blue')"),
    (["--fstop", "-2"], "the f-stop must be between 0.5 and 1024 (got -2); no lens in air is faster than f/0.5"),
    (["--fstop", "0"], "the f-stop must be between 0.5 and 1024 (got 0)"),
    (["--fstop", "inf"], "the f-stop must be between 0.5 and 1024 (got inf)"),
    (["--focus-distance", "-100"], "the focus distance must be between 0.001 and 1e+12 mm (got -100)"),
    (["--focus-distance", "inf"], "(got inf); leave it out to focus at infinity"),
    (["--sensor-width", "0"], "the sensor width must be between 0.001 and 500 mm (got 0)"),
    (["--sensor-width", "nan"], "the sensor width must be between 0.001 and 500 mm (got nan)"),
]


@pytest.mark.parametrize(("arguments", "message"), ARGUMENT_CASES, ids=[" ".join(a) for a, _ in ARGUMENT_CASES])
def test_wrong_arguments_exit_2_naming_the_option(capsys, bad_input, arguments, message):
    with pytest.raises(SystemExit) as exited:
        main([LENS, *arguments])
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert exited.value.code == 2 and message in line
    bad_input(f"lens tool: double_gauss_50mm.lens {' '.join(arguments)}", 2, line)


def test_a_focus_closer_than_the_lens_can_is_named(capsys, bad_input):
    assert main([LENS, "--focus-distance", "10"]) == 2
    line = capsys.readouterr().err.strip()
    assert line == ("prism lens: error: Lens 'Double Gauss 50mm f/2' cannot focus at 0.01 m from the film: "
                    "that is closer than it can focus. Increase the focus distance.")
    bad_input("lens tool: double_gauss_50mm.lens --focus-distance 10", 2, line)
