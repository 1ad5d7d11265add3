"""docs/performance.md: the targets, a reading of the plots, and the findings.

Every number in the document comes from ``results`` (this run's measurements);
the prose around them only says what was measured and how to read it.
"""

from __future__ import annotations

import numpy as np

from . import report

# Code observations (from reading engine/tracer and profiling a pass). Each names
# the profile entries (substring of "file:line(function)") whose cumulative time
# the document quotes from this run's profile.
OBSERVATIONS = [
    (["'compress'"],
     "Path compaction (`path_state.compact`) calls `np.compress` once per state array - up to 15 arrays, two "
     "or three times a bounce. Packing the float state (o, d, beta, mis_o, pdfs, eta) into one [n, F] array "
     "compacts it in one call, and skipping compaction while only a few paths have ended (carrying them "
     "masked) saves most copies on the early bounces, where nearly every path survives."),
    (["sampling.py", "(along)"],
     "Vectors are [N, 3] row-major and processed column by column (`along`, `to_world`, `offset_origin`): "
     "each column is a strided view. A structure-of-arrays layout ([3, N]) makes those passes contiguous."),
    (["sampling.py", "(dot)"],
     "Row-wise dot products (`sampling.dot`, called hundreds of times a pass) each read two strided [N, 3] "
     "arrays; with a [3, N] layout a dot is three contiguous multiply-adds."),
    (["cie.py", "lerp_uniform_table"],
     "The colour-matching functions are already looked up by direct index (no binary search); what is left "
     "is their evaluation for every wavelength of every path, which the estimator needs."),
]


def _short(key):
    """``engine/tracer/x.py:12(f)`` -> ``x.py:12(f)``; a builtin's ``~:0(<...>)`` -> ``<...>``."""
    return key[4:-1] if key.startswith("~:0(") else key.split("/")[-1]


def _profile_share(profile, needles):
    """(cumulative seconds, share of the pass) of the entry matching every needle,
    summed over matching entries for a <genexpr>, else the largest."""
    hits = [(k, v) for k, v in profile.get("functions", {}).items() if all(n in k for n in needles)]
    if not hits:
        return None
    if "<genexpr>" in needles or "(work)" in needles:
        seconds = sum(v[1] for _, v in hits)
        names = ", ".join(sorted(_short(k) for k, _ in hits))
    else:
        name, v = max(hits, key=lambda kv: kv[1][1])
        seconds, names = v[1], _short(name)
    return seconds, seconds / profile["total"], names


def _pct(x):
    return "n/a" if x is None or not np.isfinite(x) else f"{100 * x:.0f} %"


def _status(ok):
    return "**met**" if ok else "**not met**"


def _targets(results):
    lines = ["| target | measured | status |", "|---|---|---|"]
    ceil = next((c for c in results.get("ceiling", []) if c["scene"] == "cornell_glass"), None)
    if ceil:
        f = ceil["fraction"]
        gap = "" if f >= report.TARGET_CEILING else f" ({report.TARGET_CEILING / f:.1f}x short)"
        lines.append(f"| throughput >= 60 % of the embreex ceiling (Cornell box + glass) | {_pct(f)} "
                     f"({ceil['samples_per_second']:.0f} of {ceil['ceiling_samples_per_second']:.0f} samples/s)"
                     f"{gap} | {_status(f >= report.TARGET_CEILING)} |")
    else:
        lines.append("| throughput >= 60 % of the embreex ceiling (Cornell box + glass) | not measured | - |")
    comps = results.get("peer_comparisons", [])
    if comps:
        for c in comps:
            ratio, note = c["ratio"], f" at {c['seconds']:.2f} s"
            if c["extrapolated"] and np.isfinite(c.get("ratio_render_only", float("nan"))):
                # the curves do not overlap in total time (scene set-up dominates): use render time
                ratio, note = c["ratio_render_only"], " at equal render time, set-up excluded (total times do not overlap)"
            elif c["extrapolated"]:
                note += " (extrapolated)"
            lines.append(f"| equal-time relMSE no worse than {c['peer']} ({c['scene']}) | Prism / peer = "
                         f"{ratio:.2f}{note} | {_status(ratio <= 1.0)} |")
    else:
        lines.append("| equal-time relMSE no worse than Mitsuba 3 and Cycles | not measured | - |")
    hero = results.get("hero")
    row = next((r for r in (hero or {}).get("rows", []) if r["label"].startswith("cie x4")), None)
    if row:
        ext = " (extrapolated)" if row["extrapolated"] or hero["gaussian_extrapolated"] else ""
        lines.append(f"| cie hero reaches relMSE 1e-2 on the prism >= 4x faster than gaussian_rgb | "
                     f"{row['ratio']:.2f}x ({row['seconds']:.2f} s vs {hero['gaussian_seconds']:.2f} s){ext} | "
                     f"{_status(row['ratio'] >= report.TARGET_HERO_SPEEDUP)} |")
    else:
        lines.append("| cie hero reaches relMSE 1e-2 on the prism >= 4x faster than gaussian_rgb | not measured | - |")
    return "\n".join(lines)


def _reading(results):
    out = []
    ceil = next((c for c in results.get("ceiling", []) if c["scene"] == "cornell_glass"), None)
    if ceil:
        out.append(
            f"- **Ceiling.** On the Cornell box with glass a {ceil['samples_per_pass']}-path pass takes "
            f"{ceil['pass_seconds']:.3f} s; the {ceil['rays_recorded']} rays it sent to Embree "
            f"({ceil['closest_rays']} closest-hit, the rest shadow rays) take {ceil['embree_seconds']:.3f} s on a "
            f"bare embreex scene with the same {ceil['threads']} threads, so {_pct(ceil['fraction'])} of a pass is "
            "ray casting: the rest is numpy shading, sampling and film work (see the profile). Across scenes: "
            + ", ".join(f"{c2['scene']} {_pct(c2['fraction'])}" for c2 in results.get("ceiling", []))
            + "; the more triangles, the larger Embree's share of the same per-ray numpy work.")
    ts = results.get("thread_scaling")
    if ts:
        line = (f"- **Threads.** On {ts['scene']}, going from 1 to 2 threads made a pass {ts['prism_speedup']:.2f}x "
                f"faster ({ts['prism_1']:.3f} s -> {ts['prism_2']:.3f} s) while embreex on the same rays got "
                f"{ts['embree_speedup']:.2f}x faster ({ts['embree_1']:.4f} s -> {ts['embree_2']:.4f} s), measured "
                "interleaved in the same minute. ")
        if ts["embree_speedup"] < 1.3:
            line += ("Embree itself did not scale here (batches too small to split, or no second core free), "
                     "so this run says nothing about the renderer's threading.")
        elif ts["prism_speedup"] < 0.8 * ts["embree_speedup"]:
            line += ("Embree releases the GIL for its whole batch, but the many small numpy calls of a bounce "
                     "hold it between kernels, so the shading work of two chunks partly serialises.")
        else:
            line += "The renderer keeps most of Embree's scaling."
        out.append(line)
    for c in results.get("peer_comparisons", []):
        direction = "lower" if c["ratio"] < 1 else "higher"
        ttime = "" if not np.isfinite(c["time_ratio"]) else (
            f"; {c['peer']} reaches that error of Prism's in {c['peer_seconds_to_prism_error']:.2f} s, "
            f"{c['time_ratio']:.1f}x sooner" + (" (extrapolated)" if c["time_extrapolated"] else ""))
        render_only = c.get("ratio_render_only", float("nan"))
        if c["extrapolated"]:
            total = ("Total times do not overlap (one renderer's first image comes after the other's last, the scene "
                     "set-up dominating), so no equal-total-time figure is given. ")
        else:
            total = (f"At {c['seconds']:.2f} s Prism's relMSE is {c['prism_relmse']:.3g}, {c['peer']}'s "
                     f"{c['peer_relmse']:.3g}: Prism's error is {c['ratio']:.2f}x, i.e. {direction}{ttime}. ")
        if np.isfinite(render_only):
            total += (f"Without scene set-up on either side (Prism's Renderer construction, Mitsuba's load_dict: "
                      f"both build a BVH) the ratio at equal render time is {render_only:.2f}x. ")
        out.append(
            f"- **{c['peer']} on {c['scene']}.** " + total +
            f"Median pixel ratio of the two references (peer / Prism) is {c['convention_ratio']:.3f}, so the light "
            "units agree; each renderer is still scored against its own reference (different pixel filters).")
    hero = results.get("hero")
    if hero:
        parts = ", ".join(f"{r['label']} {r['seconds']:.2f} s" + ("*" if r["extrapolated"] else "")
                          for r in hero["rows"])
        out.append(
            f"- **Hero wavelengths on the prism.** Time to relMSE 1e-2: gaussian_rgb "
            f"{hero['gaussian_seconds']:.2f} s" + ("*" if hero["gaussian_extrapolated"] else "") +
            f"; {parts} (* = extrapolated along the curve's last segment). Each mode is scored against its own "
            "reference, since gaussian_rgb's channels are not CIE RGB and converge to a different image.")
        out.append(_hero_why(results))
    for name, entry in results["scenes"].items():
        strategies = entry.get("strategies", [])
        if len(strategies) < 2:
            continue
        base = strategies[0]["curve"][-1]
        same = [s for s in strategies[1:] if s["reference"] == strategies[0]["reference"]]
        if not same:
            continue
        effs = ", ".join(
            f"{s['label']} {base['relmse'] * base['seconds'] / (s['curve'][-1]['relmse'] * s['curve'][-1]['seconds']):.2f}x"
            for s in same)
        out.append(f"- **{name}.** Efficiency (1 / (relMSE x time)) relative to {strategies[0]['label']}: {effs}.")
    return "\n".join(out) if out else "No measurements."


def _hero_why(results):
    entry = results["scenes"]["prism"]
    by_label = {s["label"]: s for s in entry["strategies"]}
    cie, gauss = by_label.get("cie x4 (default)"), by_label.get("gaussian_rgb")
    if not (cie and gauss):
        return ""
    c, g = cie["curve"][-1], gauss["curve"][-1]
    px = entry["resolution"] ** 2
    neg = entry.get("references", {}).get("cie", {}).get("negative_fraction")
    text = (
        f"  Why: at {c['spp']} spp cie x4 took {c['seconds']:.2f} s and gaussian_rgb {g['seconds']:.2f} s for "
        f"{c['rays'] / (c['spp'] * px):.2f} vs {g['rays'] / (g['spp'] * px):.2f} rays per sample, with relMSE "
        f"{c['relmse']:.3g} vs {g['relmse']:.3g}. The camera paths that carry the rainbow meet the dispersive "
        "prism at their first hit, where both modes keep only their hero wavelength (the strategy line says "
        "so): after it cie xK carries one wavelength, as gaussian_rgb does, so the K-wavelengths-per-path "
        "advantage of hero sampling does not exist in this scene (cie x1 to x8 differ little above).")
    if neg is not None:
        text += (f" The cie estimate also maps one wavelength's XYZ into Rec.709, where the rainbow's spectral "
                 f"colours lie outside the gamut ({100 * neg:.1f} % of the cie reference's pixels have a negative "
                 "channel), so its per-sample noise relative to the pixel is larger than gaussian_rgb's, whose "
                 "channels are positive wavelength bands.")
    return text


def _ceiling_table(results):
    rows = ["| scene | threads | pass (s) | embreex on the same rays (s) | fraction | samples/s | ceiling samples/s | "
            "rays recorded | rays in stats |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for c in results.get("ceiling", []):
        rows.append(f"| {c['scene']} | {c['threads']} | {c['pass_seconds']:.3f} | {c['embree_seconds']:.4f} | "
                    f"{_pct(c['fraction'])} | {c['samples_per_second']:.0f} | {c['ceiling_samples_per_second']:.0f} | "
                    f"{c['rays_recorded']} | {c['rays_counted']} |")
    return "\n".join(rows)


def _observations(results):
    profile = results.get("profile")
    if not profile:
        return "- (no profile in this run)"
    out = []
    for needles, prose in OBSERVATIONS:
        share = _profile_share(profile, needles)
        if share is None:
            continue
        seconds, fraction, names = share
        out.append(f"- {prose}\n  Profile: `{names}` {seconds:.3f} s cumulative of the {profile['total']:.3f} s "
                   f"pass ({_pct(fraction)}).")
    embree = _profile_share(profile, ["accel.py", "(work)"])
    if embree:
        out.append(f"- Embree itself (`accel.py` `work`, the `run` calls) is {embree[0]:.3f} s of the "
                   f"{profile['total']:.3f} s single-threaded pass ({_pct(embree[1])}); the rest is numpy work "
                   "spread over many kernels of similar size. No single contained change closes the gap to 60 % "
                   "of the ceiling: that needs fewer full-array passes per bounce (fused kernels, e.g. numba, "
                   "or a compiled shading loop), which is a design change, not a patch.")
    return "\n".join(out)


def document(results, tables, plots, rel):
    cfg = results["config"]
    m = results["machine"]
    parts = [
        "# Performance: speed against error",
        "",
        "Generated by `python -m benchmarks.run" + (" --quick" if cfg["quick"] else "") + f"` on "
        f"{results['started']} ({results['total_seconds']:.0f} s). Do not edit by hand: rerun the harness "
        "(`make bench`).",
        "",
        f"Machine: {m['cpu']}, {m['cores']} cores, Python {m['python']}; load average at start "
        f"{m['load_start'][0]:.1f}, at end {m['load_end'][0]:.1f} (other work on the machine slows every "
        "renderer alike; every comparison below is a ratio measured in the same run).",
        "",
        "## Targets",
        "",
        _targets(results),
        "",
        "## Reading the plots",
        "",
        _reading(results),
        "",
        "## Method",
        "",
        f"- Images {cfg['resolution']} x {cfg['resolution']} unless a scene says otherwise (the prism is "
        "smaller, to afford the samples its rainbow needs); Prism renders progressively in passes of "
        f"{cfg['pass_spp']} spp and is measured at {', '.join(map(str, cfg['checkpoints']))} spp (per scene below); "
        f"{cfg['repeats']} repeats with different seeds, run round-robin over a scene's strategies (a change in the "
        "machine's load falls on all of them), medians of time and error reported. "
        f"{cfg['threads']} threads unless the strategy says otherwise. On a shared 2-core machine a strategy's "
        "time moves between runs (the tables show each point's min-max over the repeats): read efficiency "
        "ratios near 1 as ties. Errors are deterministic for a seed, so relMSE and FLIP repeat exactly.",
        "- Time = from the scene in memory to the image: Prism's `Renderer(...)` construction (scene analysis, "
        "BVH) plus its passes; Mitsuba's `load_dict` plus `render`; Cycles' `bpy.ops.render.render` (scene "
        "sync, BVH, render). Each process is warmed up once first (imports, JIT kernels), untimed.",
        f"- relMSE = mean((x - ref)^2 / (ref^2 + eps)) over pixels and RGB, eps = {cfg['relmse_epsilon']}, "
        "scene-linear Rec.709. FLIP = mean HDR-FLIP (flip-evaluator, 67 ppd). References: "
        f"{cfg['ref_spp']} spp for Prism unless a scene says otherwise (or {cfg['ref_max_seconds']:.0f} s, whichever first), cached in "
        "benchmarks/cache/ with their variance images; each table notes the reference's noise floor "
        "(expected relMSE contributed by the reference's own noise).",
        "- Peers run in their own processes with the same triangles, camera, light power and thread count: "
        "Mitsuba 3 `llvm_ad_spectral` (box filter, independent sampler, emitters hidden from the camera as "
        "Blender lights are) and Cycles through the bpy module on the CPU (no denoising, no adaptive sampling, "
        "its default 1.5 px Blackman-Harris filter). Each is scored against its own high-sample reference.",
        "",
        "## Ceiling: path throughput against bare embreex",
        "",
        "One pass's ray batches (closest-hit and shadow) are recorded from the renderer's `Accel` and replayed "
        "on a bare embreex scene of the same triangles with the same thread count; fraction = embreex time / "
        "pass time.",
        "",
        _ceiling_table(results),
        "",
    ]
    for name, table in tables.items():
        entry = results["scenes"][name]
        refs = ", ".join(f"{k}: {v['spp']} spp, {v['seconds']:.0f} s, noise floor {v['noise_floor']:.2g}"
                         for k, v in entry.get("references", {}).items())
        strategy = entry["strategies"][0]["strategy"]
        parts += [f"## {name}: {entry['description']}", "",
                  f"{entry['resolution']} x {entry['resolution']} pixels, checkpoints "
                  f"{', '.join(map(str, entry['checkpoints']))} spp, {entry['triangles']} triangles. Prism chose: `{strategy}`. References: {refs}.", ""]
        for peer in entry.get("peers", []):
            r = peer["reference"]
            parts.append(f"{peer['info']['renderer']} reference: {r['spp']} spp, noise floor "
                         f"{r['noise_floor']:.2g}; reference ratio peer/Prism (median over lit pixels) "
                         f"{peer['convention_ratio_median']:.3f}.")
            parts.append("")
        parts += [table, "", f"![{name}]({rel}/{name}.png)", ""]
    parts += ["## References", "", f"![references]({rel}/references.png)", ""]
    prof = results.get("profile")
    if prof:
        parts += ["## Profile of one pass", "",
                  f"cProfile of one {cfg['pass_spp']}-spp pass of {prof['scene']} at {prof['resolution']} x "
                  f"{prof['resolution']} ({prof['resolution'] ** 2 * cfg['pass_spp']} paths), single thread, "
                  "every chunk in the main thread, sorted by own time:", "", "```", prof["text"], "```", "",
                  "## Findings (suggested speed-ups, not applied)", "",
                  "Contained changes in the tracer that the profile points at; the benchmark harness does not "
                  "edit the renderer.", "", _observations(results), ""]
    if results.get("errors"):
        parts += ["## Not measured in this run", ""] + [f"- {e}" for e in results["errors"]] + [""]
    return "\n".join(parts)
