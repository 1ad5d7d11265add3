"""Colour noise of spiky light spectra (issue 16): with cie wavelengths following the scene's emission,
a lamp of two emission lines converges in colour as fast as a smooth one."""

from __future__ import annotations

import statistics
from contextlib import contextmanager, nullcontext

import numpy as np

from benchmarks.prism_runs import settings_for
from benchmarks.scenes import build
from engine.tracer import scene_tables
from engine.tracer.renderer import Renderer
from engine.tracer.scene import SampledSpectrum, SpectrumSpec
from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.spectra.trapezoid import trapezoid
from engine.tracer.spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM, VISIBLE_NM_GRID

TITLE = "Spiky light spectra: colour noise at equal samples"

LINES_NM = (460, 580)  # a blue and a yellow line: a white-ish lamp no smooth spectrum resembles


def _two_lines() -> SpectrumSpec:
    """Two emission lines 1 nm wide (full width at half maximum), as a tabulated spectrum."""
    wavelength_nm = VISIBLE_NM_GRID
    values = np.zeros(len(wavelength_nm))
    for line in LINES_NM:
        values[wavelength_nm == line] = 1.0
    return SpectrumSpec(kind="tabulated", table=SampledSpectrum(tuple(wavelength_nm), tuple(values), "two lines"))


LAMPS = {
    "RGB white (smooth)": SpectrumSpec(),
    "blackbody 3000 K (smooth)": SpectrumSpec(kind="blackbody", temperature_k=3000.0),
    "D65 (smooth, measured)": SpectrumSpec(kind="illuminant", illuminant="D65"),
    f"2 lines {LINES_NM[0]} + {LINES_NM[1]} nm": _two_lines(),
    "FL11 (tri-band fluorescent)": SpectrumSpec(kind="illuminant", illuminant="FL11"),
    "HP1 (sodium lamp)": SpectrumSpec(kind="illuminant", illuminant="HP1"),
}
SPIKY = {f"2 lines {LINES_NM[0]} + {LINES_NM[1]} nm", "FL11 (tri-band fluorescent)", "HP1 (sodium lamp)"}
# The scene this measures: the benchmark's grey Cornell box, its lamp's spectrum replaced.


@contextmanager
def _unguided():
    """The cie sampler as before issue 16: the visible density only (lines apart). The scene's tables build
    the guide (``scene_tables``), so that is where it is turned off."""
    build_guide = scene_tables.build_guide
    scene_tables.build_guide = lambda *_: None
    try:
        yield
    finally:
        scene_tables.build_guide = build_guide


def _lamp_white(spec):
    """The lamp's XYZ per unit luminance: the colour every lit pixel of the grey box converges to."""
    grid = np.linspace(VISIBLE_MIN_NM, VISIBLE_MAX_NM, 47001)
    xyz = trapezoid(emission_spectrum(spec).evaluate(grid)[:, None] * cie.cie_xyz_cmf(grid), grid, axis=0)
    return xyz / xyz[1]


def _colour_noise(image, expected_y, white):
    """RMS over lit pixels of the chromatic error |XYZ − Y · white| relative to the pixel's converged
    luminance: what is left of a pixel's error once its brightness is right (a black sample has none)."""
    xyz = cie.linear_rec709_to_xyz(image.astype(np.float64))
    lit = expected_y > 0
    residual = xyz[lit] - xyz[lit][:, 1:2] * white
    return float(np.sqrt(np.mean(np.sum(residual**2, axis=-1) / expected_y[lit] ** 2)))


def _render(scene, spec, checkpoints, seed, guided):
    scene.lights[0].spectrum = spec
    settings = settings_for({}, max(checkpoints), seed, threads=2)
    settings.samples_per_pass = min(checkpoints)
    with (nullcontext() if guided else _unguided()):
        renderer = Renderer(scene, settings)
    images = {}
    try:
        while renderer.samples_done < max(checkpoints):
            renderer.render_pass()
            if renderer.samples_done in checkpoints:
                images[renderer.samples_done] = renderer.image_rgb()
    finally:
        renderer.close()
    return images, renderer.strategy


def run(quick: bool) -> dict:
    resolution = (32, 32) if quick else (64, 64)
    checkpoints = (4, 16) if quick else (4, 16, 64)
    seeds = (1,) if quick else (1, 2, 3)
    scene = build("cornell_grey", resolution)
    # Every lamp has luminance 1 per watt: one converged luminance image serves them all.
    converged, _ = _render(scene, SpectrumSpec(), (256,), 99, True)
    expected_y = cie.linear_rec709_to_xyz(converged[256].astype(np.float64))[..., 1]
    expected_y = np.where(expected_y > 0.02 * np.median(expected_y[expected_y > 0]), expected_y, 0.0)
    rows = []
    for name, spec in LAMPS.items():
        for guided in (True, False):
            white = _lamp_white(spec)
            noise = {spp: [] for spp in checkpoints}
            for seed in seeds:
                images, strategy = _render(scene, spec, checkpoints, seed, guided)
                for spp in checkpoints:
                    noise[spp].append(_colour_noise(images[spp], expected_y, white))
            row = {"lamp": name, "wavelengths": "follow emission" if "guided by" in strategy else "visible density"}
            for spp in checkpoints:
                row[f"colour noise @ {spp} spp"] = statistics.median(noise[spp])
            rows.append(row)
    return {"rows": rows, "summary": _summary(rows, resolution, checkpoints, seeds)}


def _summary(rows, resolution, checkpoints, seeds) -> str:
    spp = checkpoints[-1]
    column = f"colour noise @ {spp} spp"
    value = {(r["lamp"], r["wavelengths"]): r[column] for r in rows}
    follow = {name: value[(name, "follow emission")] for name in LAMPS}
    before = {name: value[(name, "visible density")] for name in LAMPS}
    smooth = {name: noise for name, noise in follow.items() if name not in SPIKY}
    quietest = min(smooth, key=smooth.get)
    lines = f"2 lines {LINES_NM[0]} + {LINES_NM[1]} nm"
    verdict = "no more colour noise than" if follow[lines] <= smooth[quietest] else "more colour noise than"
    gains = ", ".join(f"{name.split(' (')[0]} {before[name] / follow[name]:.3g}×" for name in LAMPS)
    return (
        f"Colour noise of the grey Cornell box ({resolution[0]} x {resolution[1]}, cie x4, 2 threads) lit by lamps "
        f"of different spectra, all of luminance 1 per watt. Grey walls only scale the light, so every lit pixel "
        f"converges to the lamp's own colour: colour noise is the RMS over lit pixels of |XYZ − Y·XYZ_lamp/Y_lamp| "
        f"divided by the pixel's converged luminance (the error left once brightness is right), median of "
        f"{len(seeds)} seed(s). With wavelengths that follow the emission, the two-line lamp shows {follow[lines]:.3g} "
        f"at {spp} spp: {verdict} the quietest smooth lamp ({quietest}: {smooth[quietest]:.3g}; noisiest "
        f"{max(smooth.values()):.3g}). Drawn from the visible density alone, as before this change, it showed "
        f"{before[lines]:.3g}. Colour noise divided by following the emission: {gains}."
    )
