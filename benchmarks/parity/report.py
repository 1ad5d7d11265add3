"""docs/parity.md from the compared scenes: how the comparison is made, one table row and one picture per
scene, the warnings Prism printed, the seed-to-seed noise and the findings."""

from __future__ import annotations

import inspect
import platform
from datetime import date

from .findings import FINDINGS
from .noise import NoiseEstimate
from .record import LUMINANCE_TOLERANCE, ParityResult

_INTRODUCTION = """\
# Scene parity with Cycles

Small scenes built by script (`benchmarks/parity/`), each exercising one of Blender's scene settings,
rendered by Prism and by Cycles ({blender}) through the bpy module at the same size, samples, bounce limit
and seed, and compared in **absolute** terms: the ratio of the images' mean Rec.709 luminance (scene-linear,
premultiplied RGB, every pixel) Prism / Cycles, and relMSE = mean over pixels and channels of
(Prism − Cycles)² / (Cycles² + 0.01). Where both engines support what a scene uses, the verdict is
|ratio − 1| < {tolerance:.0%}; where Prism does not, the verdict is the warning Prism printed for it.

Regenerate with `make parity` (`python -m benchmarks.parity.run [--scenes NAME ...] [--seeds K]`);
`tests/blender/test_parity.py` asserts each scene's verdict. Cycles is set up to be unbiased and comparable:
CPU, box pixel filter 1 px, no adaptive sampling, no denoising, no clamping, Filter Glossy 0, caustics on,
every bounce limit equal to Prism's, seed fixed (not animated). Surfaces are Diffuse BSDF or Emission only:
the harness tests how each engine reads the *scene*, not its BSDFs (those have their own Cycles tests).
Pictures: Prism left, Cycles right, sRGB transfer curve without a view transform, transparency over a grey
checkerboard, each pixel enlarged 2 ×; a red cross where Prism made no image (refused, or one of another size).
"""


def _number(value: float | None, digits: int = 4) -> str:
    return "—" if value is None else f"{value:.{digits}f}"


def _verdict_cell(result: ParityResult) -> str:
    verdict = result.verdict
    if verdict == "warned":
        return "warning (see below)"
    if verdict == "silent":
        return "**no warning**"
    if verdict == "differs":
        return "**differs**: known, xfail" if result.scene.known_difference else "**differs** (finding)"
    return verdict


def _table(results: list[ParityResult], noise: dict[str, NoiseEstimate]) -> list[str]:
    columns = ("scene", "exercises", "spp", "Prism / Cycles mean Y", "relMSE", "mean \\|Δα\\|", "ratio noise (1σ)",
               "verdict")
    lines = ["| " + " | ".join(columns) + " |", "|---|---|---:|---:|---:|---:|---:|---|"]
    for result in results:
        scene = result.scene
        spread = noise.get(scene.name)
        noise_cell = f"{spread.ratio_spread:.2%}" if spread else "—"
        lines.append(f"| [{scene.name}](#{scene.name.replace('_', '-')}) | {scene.exercises} | {scene.samples} | "
                     f"{_number(result.ratio)} | {_number(result.rel_mse)} | {_number(result.alpha_difference)} | "
                     f"{noise_cell} | {_verdict_cell(result)} |")
    return lines


def _scene_section(result: ParityResult) -> list[str]:
    scene = result.scene
    description = " ".join(inspect.cleandoc(scene.build.__doc__).split())
    lines = [f"### {scene.name}", "", f"*{scene.exercises}.* {description}", ""]
    if result.picture:
        lines += [f"![{scene.name}: Prism left, Cycles right]({result.picture})", ""]
    seconds = f"Render time Prism {result.prism.seconds:.1f} s, Cycles {result.cycles.seconds:.1f} s"
    lines += [f"Mean luminance ratio {_number(result.ratio)}, relMSE {_number(result.rel_mse)}. {seconds}.", ""]
    if result.prism.error:
        lines += [f"Prism refused: `{result.prism.error}`", ""]
    for warning in result.prism.warnings:
        lines += [f"Prism warned: `{warning}`", ""]
    if scene.name in FINDINGS:
        lines += [FINDINGS[scene.name].strip(), ""]
    return lines


def _noise_section(noise: dict[str, NoiseEstimate]) -> list[str]:
    lines = ["## Noise", ""]
    if not noise:
        return lines + ["Not measured in this run (`--seeds K` renders every scene with K seeds per engine).", ""]
    seeds = max(n.seeds for n in noise.values())
    lines += [f"Every scene rendered by both engines with seeds 0 … {seeds - 1} at its sample count: the relative "
              "standard deviation of each engine's mean luminance and of the ratio (seed k against seed k), and "
              f"how many of those standard deviations fit inside the {LUMINANCE_TOLERANCE:.0%} tolerance.", "",
              "| scene | Prism σ | Cycles σ | ratio σ | tolerance / σ | ratios |", "|---|---:|---:|---:|---:|---|"]
    for name, n in noise.items():
        ratios = ", ".join(f"{r:.4f}" for r in n.ratios)
        lines.append(f"| {name} | {n.prism_spread:.2%} | {n.cycles_spread:.2%} | {n.ratio_spread:.2%} | "
                     f"{n.margin_sigmas:.1f} | {ratios} |")
    return lines + [""]


def write_report(path, results: list[ParityResult], noise: dict[str, NoiseEstimate], blender_version: str) -> None:
    """Write the whole document to ``path``."""
    introduction = _INTRODUCTION.format(blender=f"Blender {blender_version}", tolerance=LUMINANCE_TOLERANCE)
    machine = f"{platform.machine()} ({platform.system()})"
    lines = [introduction, "## Results", "",
             f"Measured {date.today().isoformat()} on {machine}, 2 threads per engine.", ""]
    lines += _table(results, noise) + [""]
    matched = sum(r.verdict == "match" for r in results)
    warned = sum(r.verdict == "warned" for r in results)
    lines += [f"{matched} of {len(results)} scenes within {LUMINANCE_TOLERANCE:.0%}; {warned} answered by the "
              f"warning Prism prints; {len(results) - matched - warned} differ (see Findings).", ""]
    if "general" in FINDINGS:
        lines += ["## Findings", "", FINDINGS["general"].strip(), ""]
    lines += _noise_section(noise)
    lines += ["## Scenes", ""]
    for result in results:
        lines += _scene_section(result)
    path.write_text("\n".join(lines).rstrip() + "\n")
