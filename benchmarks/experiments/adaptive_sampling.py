"""Adaptive sampling against uniform sampling at equal time on a scene with uneven noise."""

from __future__ import annotations

TITLE = "Adaptive sampling: relMSE at equal time against uniform sampling"


def run(quick: bool) -> dict:
    from benchmarks import scenes
    from benchmarks.metrics import relmse

    from ._common import reference, render

    resolution, seconds, repeats, reference_spp = (48, 2.0, 1, 512) if quick else (96, 8.0, 3, 2048)
    truth, _ = reference("cornell_glass", resolution, reference_spp)
    scene = scenes.build("cornell_glass", (resolution, resolution))
    variants = {
        "uniform": {"time_limit_s": seconds, "samples_per_pass": 4},
        "adaptive": {"time_limit_s": seconds, "samples_per_pass": 4, "adaptive_threshold": 0.05,
                     "adaptive_min_samples": 32},
    }
    rows = []
    for repeat in range(repeats):
        for name, overrides in variants.items():  # interleaved: a busy moment slows both alike
            image, _, took, counts, _ = render(scene, overrides, 1 << 20, seed=10 + repeat)
            rows.append({"variant": name, "repeat": repeat, "seconds": round(took, 2), "relMSE": relmse(image, truth),
                         "mean spp": float(counts.mean()), "min spp": int(counts.min()),
                         "max spp": int(counts.max())})

    def median(name):
        values = sorted(r["relMSE"] for r in rows if r["variant"] == name)
        return values[len(values) // 2]

    uniform, adaptive = median("uniform"), median("adaptive")
    summary = (
        f"Cornell box with an N-SF11 glass ball (a caustic under the ball, plain walls), {resolution} x "
        f"{resolution}, each variant given the same time limit of {seconds:g} s of sampling (2 threads, 4 spp "
        f"per pass), {repeats} interleaved repeat(s), median relMSE against a {reference_spp} spp reference. "
        f"Adaptive: noise threshold 0.05, 32 min samples. Uniform {uniform:.3g}, adaptive {adaptive:.3g}: "
        f"adaptive is {uniform / adaptive:.2f}x lower."
    )
    return {"rows": rows, "summary": summary}
