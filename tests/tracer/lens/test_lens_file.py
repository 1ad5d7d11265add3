"""Lens prescription files: the pbrt/CS184 table, Prism's .lens, and every kind of bad file."""

import math

import pytest

from engine.tracer.errors import LensFileError, PrismInputError
from engine.tracer.spectra.glass import glass_by_name, nearest_catalogue_glass
from engine.tracer.lens.catalogue import LENS_DIRECTORY, bundled_lenses
from engine.tracer.lens.lens_file import load_lens
from engine.tracer.lens.paraxial import paraxial_data

# The pbrt/CS184 table of the double Gauss (Tronnier, US 2,673,491; W. J. Smith, Modern Lens
# Design, p. 312; scaled to 50 mm): radius, thickness, n_d, aperture diameter, mm.
DGAUSS_DAT = """# D-GAUSS F/2
#    radius	 axpos	N	aperture
29.475	3.76	1.67	25.2
84.83	0.12	1	25.2
19.275	4.025	1.67	23
40.77	3.275	1.699	23
12.75	5.705	1	18
0	4.5	0	17.1
-14.495	1.18	1.603	17
40.77	6.065	1.658	20
-20.385	0.19	1	20
437.065	3.22	1.717	20
-39.73	0	1	20
"""


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_dat_columns_are_radius_thickness_index_and_diameter(tmp_path):
    lens = load_lens(_write(tmp_path, "dgauss.dat", DGAUSS_DAT))
    assert len(lens.surfaces) == 11 and lens.stop_index == 5
    first = lens.surfaces[0]
    assert (first.radius_mm, first.thickness_mm, first.aperture_mm, first.semi_aperture_mm) == (29.475, 3.76, 25.2, 12.6)
    assert lens.surfaces[1].medium.is_air and lens.surfaces[5].medium.is_air  # n = 1 and the stop's n = 0
    assert lens.surfaces[5].is_stop and math.isinf(lens.surfaces[5].radius_mm)
    assert lens.vertex_z_mm[-1] == pytest.approx(32.04)
    assert lens.name == "D-GAUSS F/2"


def test_dat_keeps_n_d_and_takes_v_d_from_the_nearest_catalogue_glass(tmp_path):
    lens = load_lens(_write(tmp_path, "dgauss.dat", DGAUSS_DAT))
    for surface, n_d in ((0, 1.67), (3, 1.699), (6, 1.603)):
        medium = lens.surfaces[surface].medium
        assert medium.n_d == pytest.approx(n_d, abs=1e-12)
        assert medium.v_d == pytest.approx(nearest_catalogue_glass(n_d).v_d, rel=1e-9)
    assert any("n_d 1.699" in note and "SF1" in note for note in lens.notes)
    assert any("n_d 1.603" in note and "N-SK2" in note for note in lens.notes)


def test_every_bundled_lens_loads_and_has_its_nominal_focal_length():
    entries = bundled_lenses()
    stems = {e[0] for e in entries}
    assert {"double_gauss_50mm", "wide_angle_22mm", "fisheye_10mm", "telephoto_250mm",
            "achromat_100mm", "singlet_bk7_100mm"} <= stems
    for stem, name, path in entries:
        lens = load_lens(path)
        assert lens.name == name and lens.source
        efl = paraxial_data(lens).efl_mm
        assert efl == pytest.approx(lens.nominal_focal_length_mm, rel=0.01), stem


def test_bundled_double_gauss_matches_its_reference_table(tmp_path):
    prism = load_lens(LENS_DIRECTORY / "double_gauss_50mm.lens")
    legacy = load_lens(_write(tmp_path, "dgauss.50mm.dat", DGAUSS_DAT))
    assert len(prism.surfaces) == len(legacy.surfaces) == 11
    for a, b in zip(prism.surfaces, legacy.surfaces):
        assert (a.radius_mm, a.thickness_mm, a.aperture_mm, a.is_stop) == (b.radius_mm, b.thickness_mm, b.aperture_mm, b.is_stop)
        assert a.medium.n_d == pytest.approx(b.medium.n_d, abs=1e-3)
    # Abbe numbers from the design's table (Smith, Modern Lens Design, p. 312), glass elements in order.
    glass_v_d = [s.medium.v_d for s in prism.surfaces if s.medium.n_d > 1.01]
    assert glass_v_d == pytest.approx([47.1, 47.1, 30.1, 38.0, 57.3, 48.0], abs=0.05)


def test_prism_format_glass_by_name_by_abbe_and_air(tmp_path):
    text = """name = "Test"
source = "test"
f_number = 8

[[surface]]
stop = true
thickness_mm = 2
aperture_mm = 10

[[surface]]
radius_mm = 50
thickness_mm = 4
aperture_mm = 20
glass = "N-BK7"

[[surface]]
radius_mm = -50
thickness_mm = 2
aperture_mm = 20
nd = 1.7
vd = 30

[[surface]]
radius_mm = inf
aperture_mm = 20
glass = "air"
"""
    lens = load_lens(_write(tmp_path, "t.lens", text))
    assert lens.surfaces[1].medium.n_d == pytest.approx(1.5168, abs=1e-4)
    assert lens.surfaces[2].medium.n_d == pytest.approx(1.7) and lens.surfaces[2].medium.v_d == pytest.approx(30)
    assert lens.surfaces[3].medium.is_air and lens.surfaces[3].thickness_mm == 0.0
    assert lens.nominal_f_number == 8.0


BAD_DAT_CASES = [
    ("29.475\t3.76\t1.67\n0\t1\t0\t10\n", r"bad\.dat, line 1: expected 4 columns .* found 3"),
    ("29.475\t3.76\tglass\t25\n0\t1\t0\t10\n", r"line 1, column 3 \(index\): 'glass' is not a finite number"),
    ("# c\n29.475\t3.76\t1.67\t-25.2\n84.83\t1\t1\t25.2\n0\t1\t0\t10\n", r"line 2: negative clear aperture -25.2 mm"),
    ("29.475\t3.76\t1.67\t25.2\n84.83\t1\t1\t25.2\n", r"no aperture stop"),
    ("0\t1\t0\t10\n20\t0.5\t1.5\t30\n-20\t1\t1\t30\n", r"line 3: this surface cuts through the previous one \(line 2\)"),
    ("0\t1\t0\t10\n20\t5\t0.5\t10\n-20\t1\t1\t10\n", r"line 2, column 3 \(index\): 0.5 is not a refractive index"),
]


@pytest.mark.parametrize("text, message", BAD_DAT_CASES,
                         ids=["columns", "non-numeric", "negative-aperture", "no-stop", "intersecting", "index"])
def test_malformed_dat_files_name_file_line_and_problem(tmp_path, text, message):
    path = _write(tmp_path, "bad.dat", text)
    with pytest.raises(LensFileError, match=message) as error:
        load_lens(path)
    assert str(path) in str(error.value)


GOOD_HEAD = 'name = "Bad"\n\n[[surface]]\nstop = true\nthickness_mm = 2\naperture_mm = 10\n\n'


@pytest.mark.parametrize("surface, message", [
    ('[[surface]]\nradius_mm = 50\nthickness_mm = 4\naperture_mm = 20\nglass = "N-BK77"\n',
     r"line 12 \(surface 2, 'glass'\): unknown glass 'N-BK77'\. Known glasses: N-BK7"),
    ('[[surface]]\nradius_mm = 50\nthickness_mm = 4\naperture_mm = -20\nglass = "N-BK7"\n',
     r"line 9: negative clear aperture"),
    ('[[surface]]\nradius_mm = "fifty"\nthickness_mm = 4\naperture_mm = 20\n',
     r"line 9 \(surface 2, 'radius_mm'\): 'fifty' is not a number"),
    ('[[surface]]\nradius_mm = 50\nthickness_mm = 4\naperture_mm = 20\nthickness = 3\n',
     r"line 12 \(surface 2, 'thickness'\): unknown key"),
    ('[[surface]]\nradius_mm = 50\nthickness_mm = 4\naperture_mm = 20\nglass = \n',
     r"not valid TOML: .*line 12"),
])
def test_malformed_prism_lens_files(tmp_path, surface, message):
    tail = '\n[[surface]]\nradius_mm = -50\naperture_mm = 20\n'
    path = _write(tmp_path, "bad.lens", GOOD_HEAD + surface + tail)
    with pytest.raises(LensFileError, match=message):
        load_lens(path)


def test_missing_file_and_missing_stop_in_prism_format(tmp_path):
    with pytest.raises(LensFileError, match=r"Lens file '.*nowhere\.lens' does not exist"):
        load_lens(tmp_path / "nowhere.lens")
    text = 'name = "x"\n[[surface]]\nradius_mm = 50\nthickness_mm = 4\naperture_mm = 20\nglass = "N-BK7"\n' \
           '[[surface]]\nradius_mm = -50\naperture_mm = 20\n'
    with pytest.raises(LensFileError, match="no aperture stop"):
        load_lens(_write(tmp_path, "nostop.lens", text))
    assert issubclass(LensFileError, PrismInputError)
