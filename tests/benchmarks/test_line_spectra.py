"""The line-spectra experiment's switch back to unguided wavelengths (``line_spectra._unguided``) reaches the
renderer: a lamp of two emission lines gets wavelengths that follow its emission, and inside the switch the
visible density alone (the strategy line says which)."""

from contextlib import nullcontext

from benchmarks.experiments import line_spectra
from benchmarks.prism_runs import settings_for
from benchmarks.scenes import build
from engine.tracer.renderer import Renderer


def _strategy(guided):
    scene = build("cornell_grey", (8, 8))
    scene.lights[0].spectrum = line_spectra._two_lines()
    with (nullcontext() if guided else line_spectra._unguided()):
        renderer = Renderer(scene, settings_for({}, 1, 1, threads=1))
    try:
        return renderer.strategy
    finally:
        renderer.close()


def test_the_unguided_switch_turns_the_wavelength_guide_off():
    assert "guided by" in _strategy(True)
    assert "guided by" not in _strategy(False)
