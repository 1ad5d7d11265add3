"""Denoising a 16 spp Cornell box with a glass ball with OpenImageDenoise guided by Prism's passes."""

from __future__ import annotations

import time

TITLE = "Denoising: relMSE of a 16 spp frame before and after OpenImageDenoise"


def run(quick: bool) -> dict:
    from benchmarks import scenes
    from benchmarks.metrics import relmse, relmse_noise_floor
    from engine.output.denoise import denoise
    from engine.tracer.pass_table import PassRequest

    from ._common import reference, render

    resolution, reference_spp, seeds = (48, 512, (0,)) if quick else (96, 2048, (0, 1, 2))
    truth, truth_variance = reference("cornell_glass", resolution, reference_spp)
    floor = relmse_noise_floor(truth, truth_variance)
    scene = scenes.build("cornell_glass", (resolution, resolution))
    guides = PassRequest(("Denoising Albedo", "Denoising Normal"))
    rows = []
    for seed in seeds:
        image, passes, seconds, _, _ = render(scene, {"passes": guides}, 16, seed=seed)
        started = time.perf_counter()
        guided = denoise(image, passes["Denoising Albedo"], passes["Denoising Normal"])
        guided_seconds = time.perf_counter() - started
        alone = denoise(image)
        noisy_error = relmse(image, truth)
        rows.append({"seed": seed, "relMSE noisy": noisy_error, "relMSE denoised": relmse(guided, truth),
                     "relMSE denoised (image only)": relmse(alone, truth),
                     "gain (noisy / denoised)": noisy_error / relmse(guided, truth),
                     "render (s)": round(seconds, 2), "denoise (s)": round(guided_seconds, 2)})
    gains = sorted(r["gain (noisy / denoised)"] for r in rows)
    median = gains[len(gains) // 2]
    summary = (
        f"Cornell box with an N-SF11 glass ball, {resolution} x {resolution}, 16 spp (cie x4, Sobol, 2 threads), "
        f"denoised by Blender's OpenImageDenoise (RT filter, HDR, prefilter Accurate, quality High) guided by "
        f"Prism's Denoising Albedo and Denoising Normal passes, as Render ▸ Prism ▸ Denoise does; "
        f"{len(seeds)} seed(s). Reference: {reference_spp} spp with another seed (its own noise floor "
        f"relMSE {floor:.2g}). Median gain in relMSE: {median:.1f}x (target: at least 5x)."
    )
    return {"rows": rows, "summary": summary}
