"""Why the dispersive gem of ``spectral_gem_picture.py`` is darker than its constant-index copy: the gem's mean
luminance at constant indices, and the dispersive gem's against what those predict.

    .venv/bin/python tools/gem_index_sweep.py [--samples 512] [--quantiles 16] [--medium]

The gem without its absorbing medium (``--medium`` keeps it), no clamps, 100 x 75 px, two seeds per render. A smooth dispersive glass
shows each wavelength λ exactly what a constant-index glass of index n(λ) shows, so under lights of spectrum S
its image's luminance Y is ∫ ȳ S Y_{n(λ)} dλ / ∫ ȳ S: the mean of the constant-index renders at the ``--quantiles``
wavelengths that split ȳ S (CIE 1931; S the lights' white, upsampled against D65) into equal parts. Prints the sweep, Prism and Cycles at n_d (absolute), that prediction and
the dispersive render.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SEEDS = (0, 1)
BOUNCES = 24


def luminance_quantile_wavelengths(count: int, emission) -> np.ndarray:
    """The mid-points (nm) of ``count`` equal shares of ∫ ȳ(λ) S(λ) dλ: CIE 1931's ȳ times the lights'
    spectrum ``emission(λ)``."""
    import colour

    y = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].align(colour.SpectralShape(360, 830, 1))
    wavelengths = y.wavelengths
    weight = y.values[:, 1] * emission(wavelengths)
    cumulative = np.cumsum(weight) / weight.sum()
    return np.interp((np.arange(count) + 0.5) / count, cumulative, wavelengths)


def _mean_luminance(scene, samples: int, engine: str = "PRISM") -> float:
    from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

    if engine == "CYCLES":
        images = [render_cycles_rgba(scene, samples, seed, max_bounces=BOUNCES) for seed in SEEDS]
    else:
        images = [render_prism_rgba(scene, samples, seed) for seed in SEEDS]
    return float(np.mean([luminance(image[..., :3]).mean() for image in images]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=512)
    parser.add_argument("--quantiles", type=int, default=16)
    parser.add_argument("--medium", action="store_true",
                        help="keep the gem's absorbing medium: no prediction then (the medium weighs each wavelength "
                             "by its own path lengths), only Prism and Cycles at n_d and the dispersive gem")
    arguments = parser.parse_args()
    sys.path[:0] = [str(ROOT), str(ROOT / "tests"), str(ROOT / "tools")]
    import bpy

    from helpers.cycles import configure_cycles
    from render import load_addon_package
    from spectral_gem_picture import N_D, V_D, _scene

    package = load_addon_package()
    package.register()
    glass = importlib.import_module(f"{package.__name__}.engine.tracer.spectra.glass").glass_from_abbe(N_D, V_D)
    spectra = importlib.import_module(f"{package.__name__}.engine.tracer.spectra.emission_spectrum")
    white = spectra.RGBEmissionSpectrum((1.0, 1.0, 1.0)).evaluate  # the lights' colour, upsampled against D65
    scene = _scene(bpy)
    configure_cycles(scene, arguments.samples, max_bounces=BOUNCES)  # no clamps, no Filter Glossy (Prism reads them)
    scene.prism.max_bounces = BOUNCES
    scene.render.resolution_x, scene.render.resolution_y = 100, 75
    material = bpy.data.materials["Gem"]
    for link in [link for link in material.node_tree.links if link.to_socket.name == "Volume" and not arguments.medium]:
        material.node_tree.links.remove(link)  # the medium absorbs per wavelength: the prediction would not hold
    glass_node = next(node for node in material.node_tree.nodes if node.bl_idname == "ShaderNodeBsdfGlass")

    material.prism.glass_source = "PRINCIPLED_IOR"
    predicted = []
    sweep = [] if arguments.medium else luminance_quantile_wavelengths(arguments.quantiles, white)
    for wavelength in sweep:
        glass_node.inputs["IOR"].default_value = float(glass.index(wavelength))
        predicted.append(_mean_luminance(scene, arguments.samples))
        print(f"constant index {glass.index(wavelength):.4f} (n at {wavelength:.0f} nm): {predicted[-1]:.4f}",
              flush=True)
    glass_node.inputs["IOR"].default_value = N_D
    at_nd = _mean_luminance(scene, arguments.samples)
    cycles_at_nd = _mean_luminance(scene, arguments.samples, "CYCLES")
    material.prism.glass_source = "ABBE"
    dispersive = _mean_luminance(scene, arguments.samples)
    print(f"constant index n_d {N_D}: Prism {at_nd:.4f}, Cycles {cycles_at_nd:.4f} ({at_nd / cycles_at_nd:.4f})")
    print(f"dispersive (n_d {N_D}, V_d {V_D}): {dispersive:.4f} ({dispersive / at_nd:.4f} of n_d's)", flush=True)
    if predicted:
        print(f"predicted from the sweep {np.mean(predicted):.4f}; measured / predicted {dispersive / np.mean(predicted):.4f}")
    os._exit(0)  # bpy's exit can hang after renders


if __name__ == "__main__":
    main()
