"""The colorimetric tables Prism ships (``spectra.colorimetry_tables``) are colour-science's (data bit for bit),
and a render reads them without importing colour-science."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np

from engine.tracer.spectra import cie, colorimetry_tables, rgb_to_spectrum


def test_the_shipped_tables_equal_colour_sciences():
    # Fails when colour-science's data change: rerun tools/generate_colorimetry_tables.py. The tabulated data
    # (observer, illuminant) are equal bit for bit; the XYZ → BT.709 matrix is colour-science's inverse of the
    # primaries' matrix, whose last bit depends on the machine's LAPACK kernels (1 ulp apart on two machines with
    # the same pinned numpy and colour-science), so it is compared to 1e-14.
    shipped, computed = colorimetry_tables.load(), colorimetry_tables.from_colour_science()
    for name in colorimetry_tables.ColorimetryTables._fields:
        if name == "xyz_to_rec709":
            np.testing.assert_allclose(getattr(shipped, name), getattr(computed, name), rtol=0.0, atol=1e-14)
        else:
            assert np.array_equal(getattr(shipped, name), getattr(computed, name)), name


def test_the_tables_are_the_ones_colorimetry_uses():
    tables = colorimetry_tables.load()
    assert cie._cmf_table()[1] is tables.cmf_xyz
    assert cie.XYZ_TO_LINEAR_REC709 is tables.xyz_to_rec709
    assert rgb_to_spectrum._d65_table()[1] is tables.d65_power
    assert not tables.cmf_xyz.flags.writeable
    # The BT.709 white (D65's chromaticity, Y = 1) maps to (1, 1, 1).
    x, y = 0.3127, 0.3290
    assert np.allclose(cie.xyz_to_linear_rec709([x / y, 1.0, (1.0 - x - y) / y]), 1.0, atol=1e-12)


_UPSAMPLE = textwrap.dedent(
    """
    import sys
    sys.modules["matplotlib"] = None  # as in Blender
    sys.path[:0] = [{root!r}, {root!r} + "/tests"]
    from helpers import one_package
    one_package.install()  # the suite's package name, so its kernel cache
    import numpy as np
    from engine.tracer.spectra import cie, rgb_to_spectrum
    coefficients = rgb_to_spectrum.reflectance_coefficients(np.array([[0.8, 0.3, 0.1], [0.1, 0.2, 0.9]]))
    emission = rgb_to_spectrum.RGBEmission(np.array([2.0, 1.0, 0.5])).evaluate(np.array([450.0, 600.0]))
    y = cie.spectrum_luminance(lambda nm: np.ones_like(nm))
    print(sorted(name for name in sys.modules if name.split(".")[0] == "colour")[:3], np.isfinite(coefficients).all())
    """
)


def test_upsampling_and_colorimetry_do_not_import_colour_science():
    from engine.tracer import kernel_folder

    # The suite's kernel cache (the first guesses come from a compiled table lookup).
    environment = {"PRISM_KERNEL_CACHE": str(kernel_folder.cache_directory())}
    root = str(colorimetry_tables.TABLES_PATH.parents[4])
    done = subprocess.run([sys.executable, "-c", _UPSAMPLE.format(root=root)], capture_output=True, text=True,
                          timeout=300, cwd=root, env=environment)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.split() == ["[]", "True"], done.stdout
