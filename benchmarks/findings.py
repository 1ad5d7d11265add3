"""docs/performance.md: the targets, a reading of the measurements, what dominates a pass, and the
document's frame (header, method, sections) that places the tables of ``findings_tables.py``.

Every number in the document comes from ``results`` (this run's measurements); the prose around
them only says what was measured, how to read it, and which conclusion the numbers support.
"""

from __future__ import annotations

import numpy as np

from . import targets
from .findings_tables import (_ceiling_table, _demo_profile, _demo_section, _experiment_section, _sampler_table,
                              _stage_table, _startup_table)
from .findings_values import _embree_share, _glass_ceiling, _largest_stage, _pct, _peer_ratio, _stage_rows, _status
from .scaling import scaling_table, target_row


def _compile_split(cold: dict) -> str:
    """The cold compile's functions and LLVM seconds (``benchmarks.compile_events``), where the run recorded them."""
    if "llvm_seconds" not in cold:
        return ""
    return f", {cold['functions_compiled']} functions, {cold['llvm_seconds']:.0f} s of it in LLVM"


def _targets(results):
    lines = ["| target (issue 11) | measured in this run | status |", "|---|---|---|"]
    ceil = _glass_ceiling(results)
    if ceil:
        f = ceil["fraction"]
        gap = "" if f >= targets.TARGET_CEILING else f"; a pass must get {targets.TARGET_CEILING / f:.1f}x faster"
        lines.append(f"| path throughput >= 60 % of the embreex ceiling, cornell_glass, 2 threads | {_pct(f)} "
                     f"({ceil['samples_per_second']:,.0f} of {ceil['ceiling_samples_per_second']:,.0f} samples/s{gap}) | "
                     f"{_status(f >= targets.TARGET_CEILING)} |")
    else:
        lines.append("| path throughput >= 60 % of the embreex ceiling, cornell_glass, 2 threads | not measured | - |")
    comps = results.get("peer_comparisons", [])
    for c in comps:
        target = targets.peer_target(c["peer"])
        ratio, note, measured = _peer_ratio(c)
        bound = "no worse than" if target == 1.0 else f"within {target:g}x of"
        value = f"Prism / peer = {ratio:.3g}{note}" if measured else "the two curves do not overlap in time"
        lines.append(f"| equal-time relMSE {bound} {c['peer']}, {c['scene']} | {value} | "
                     f"{_status(ratio <= target) if measured else 'not measured'} |")
    if not comps:
        lines.append("| equal-time relMSE against Cycles and Mitsuba 3 | not measured | - |")
    gains = results.get("sampler_gain", [])
    if gains:
        text = ", ".join(f"{g['scene']} {g['gain']:.2f}x" for g in gains)
        lines.append(f"| the Sobol sampler's gain at equal spp (relMSE independent / Sobol, last checkpoint) | "
                     f"{text} | reported |")
    st = results.get("startup")
    if st:
        lines.append(f"| cold-compile and warm-start seconds (fresh process, tiny {st['scene']}) | cold "
                     f"{st['cold']['process_seconds']:.1f} s, warm {st['warm']['process_seconds']:.1f} s, import "
                     f"{st['warm']['import_seconds']:.2f} s | reported |")
    for case in results.get("scaling", {}).get("cases", []):
        lines.append(target_row(case, results["scaling"]["cores"]))
    demo = results.get("demo")
    if demo and "speedup_process" in demo:
        ok = demo["speedup_process"] >= targets.TARGET_DEMO_SPEEDUP and demo["spp"] == 64
        noise = "" if "noise" not in demo["now"] else (
            f"; noise {demo['before']['noise']:.2f} -> {demo['now']['noise']:.2f} display levels")
        lines.append(f"| `make render` (480 x 320, {demo['spp']} spp) >= 5x faster than the numpy tracer, with less "
                     f"noise | {demo['before']['process_seconds']:.1f} s -> {demo['now']['process_seconds']:.1f} s = "
                     f"{demo['speedup_process']:.2f}x{noise} | {_status(ok)} |")
    elif demo:
        lines.append(f"| `make render` >= 5x faster than the numpy tracer | now {demo['now']['process_seconds']:.1f} s; "
                     f"before not measured ({demo.get('before', {}).get('error', '-')}) | - |")
    hero = results.get("hero")
    row = next((r for r in (hero or {}).get("rows", []) if r["label"].startswith("cie x4")), None)
    if row:
        ext = " (extrapolated)" if row["extrapolated"] or hero["gaussian_extrapolated"] else ""
        lines += ["", "| earlier target | measured in this run | status |", "|---|---|---|",
                  f"| cie hero reaches relMSE 1e-2 on the prism >= 4x faster than gaussian_rgb | "
                  f"{row['ratio']:.2f}x ({row['seconds']:.2f} s vs {hero['gaussian_seconds']:.2f} s){ext} | "
                  f"{_status(row['ratio'] >= targets.TARGET_HERO_SPEEDUP)} |"]
    return "\n".join(lines)


def _reading(results):
    out = []
    ceil = _glass_ceiling(results)
    if ceil:
        split = _stage_rows(results, "cornell_glass", 2)
        where = ""
        if split:
            top = _largest_stage(split)
            where = (f" With the pass split by stage (2 threads, CPU time), Embree's queries take "
                     f"{_pct(_embree_share(split))} of it and the largest kernel, {top['stage']}, "
                     f"{_pct(top['share'])} (see *Where a pass spends its time*).")
        out.append(
            f"- **Ceiling.** On the Cornell box with glass a {ceil['samples_per_pass']:,}-path pass takes "
            f"{ceil['pass_seconds']:.3f} s; the {ceil['rays_recorded']:,} rays it sent to Embree "
            f"({ceil['closest_rays']:,} closest-hit, {ceil['shadow_rays']:,} shadow rays) take "
            f"{ceil['embree_seconds']:.4f} s on a bare embreex scene with the same {ceil['threads']} threads: "
            f"{_pct(ceil['fraction'])} of the ceiling ({_pct(ceil.get('cpu_fraction'))} in CPU time).{where} "
            "Across scenes: "
            + ", ".join(f"{c['scene']} {_pct(c['fraction'])}" for c in results.get("ceiling", [])) + ".")
    sc = results.get("scaling")
    if sc:
        kept = [(c, r) for c in sc["cases"] for r in c["rows"] if r["threads"] > 1 and not r["oversubscribed"]]
        if kept:
            worst = min(kept, key=lambda cr: cr[1]["kept"])
            out.append(f"- **Threads.** Up to the machine's {sc['cores']} cores the renderer keeps at least "
                       f"{_pct(worst[1]['kept'])} of embreex's own scaling on the same rays (least: "
                       f"{worst[0]['scene']} {worst[0]['label']} pass at T={worst[1]['threads']}); the table is in "
                       "[Thread scaling](#thread-scaling).")
    for c in results.get("peer_comparisons", []):
        direction = "lower" if c["ratio"] < 1 else "higher"
        ttime = "" if not np.isfinite(c["time_ratio"]) else (
            f"; {c['peer']} reaches that error of Prism's in {c['peer_seconds_to_prism_error']:.2f} s, "
            + (f"{c['time_ratio']:.1f}x sooner" if c["time_ratio"] >= 1 else f"{1 / c['time_ratio']:.1f}x later")
            + (" (extrapolated)" if c["time_extrapolated"] else ""))
        render_only = c.get("ratio_render_only", float("nan"))
        if c["extrapolated"]:
            total = ("Total times do not overlap (one renderer's first image comes after the other's last), so "
                     "no equal-total-time figure is given. ")
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
    gains = results.get("sampler_gain", [])
    if gains:
        parts = "; ".join(
            f"{g['scene']} " + ", ".join(f"{p['gain']:.2f}x at {p['spp']}" for p in g["points"]) for g in gains)
        out.append(f"- **Sampler.** relMSE with independent random numbers / relMSE with the Owen-scrambled Sobol "
                   f"sampler, same seeds, same spp, same reference (above 1: Sobol is better): {parts} spp.")
    st = results.get("startup")
    if st:
        c, w = st["cold"], st["warm"]
        out.append(
            f"- **Start-up.** A fresh process rendering {st['scene']} at {st['resolution']} x {st['resolution']}: "
            f"with an empty kernel cache {c['process_seconds']:.1f} s (its first pass, which compiles the kernels, "
            f"{c['first_pass_seconds']:.1f} s{_compile_split(c)}); with the cache filled {w['process_seconds']:.1f} s (first pass, "
            f"loading the kernels from disk, {w['first_pass_seconds']:.2f} s; importing the tracer "
            f"{w['import_seconds']:.2f} s; colour-science imported: "
            f"{'yes' if w.get('colour_imported', True) else 'no'}). `cache_is_warm()` said {c['cache_was_warm']} then "
            f"{w['cache_was_warm']}, so the first render alone shows \"Compiling Prism kernels\".")
    demo = results.get("demo")
    if demo:
        now = demo["now"]
        line = (f"- **Demo.** `make render`'s render (480 x 320, {demo['spp']} spp, all cores) took "
                f"{now['process_seconds']:.1f} s for the whole process (Blender's render time "
                f"{now['blender_seconds']:.1f} s; mean of {len(now['runs'])} runs)")
        before = demo.get("before", {})
        if "process_seconds" in before:
            line += (f"; the numpy tracer (commit {demo['before_commit'][:7]}) took {before['process_seconds']:.1f} s "
                     f"({before['blender_seconds']:.1f} s), the two taking turns: {demo['speedup_process']:.2f}x "
                     f"faster ({demo['speedup_blender']:.2f}x in render time).")
            if "noise" in now:
                line += (f" Noise at the same spp (RMS difference of two seeds' PNGs / sqrt 2, in 8-bit display "
                         f"levels): {before['noise']:.2f} before, {now['noise']:.2f} now "
                         f"({demo['noise_ratio']:.2f}x less).")
        else:
            line += f"; the numpy tracer was not measured ({before.get('error', 'no tree')})."
        out.append(line)
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


def _dominates(results):
    """What the stage split says, per scene and overall."""
    out = []
    for entry in results.get("stages", []):
        one, two = entry.get("1"), entry.get("2")
        if not one:
            continue
        top = _largest_stage(one)
        line = (f"- **{entry['scene']}**: with 1 thread Embree takes {_pct(_embree_share(one))} of the CPU time of a "
                f"pass and {top['stage']} {_pct(top['share'])}")
        if two:
            grown = []
            for row in one["rows"]:
                other = next((r for r in two["rows"] if r["stage"] == row["stage"]), None)
                if other and row["cpu"] > 0.001 and other["cpu"] > 1.2 * row["cpu"]:
                    grown.append(f"{row['stage']} {other['cpu'] / row['cpu']:.2f}x")
            line += (f"; with 2 threads the chunks' CPU time is {two['chunk_cpu'] / max(one['chunk_cpu'], 1e-9):.2f}x "
                     "that of 1 thread")
            if grown:
                line += " (more CPU for the same work in: " + ", ".join(grown) + ")"
            line += (f", and {_pct(two['unexplained'] / (2 * two['pass_seconds']))} of 2 x the pass's wall time "
                     "is no chunk's CPU time")
        out.append(line + ".")
    ceil = _glass_ceiling(results)
    if ceil and ceil["fraction"] < targets.TARGET_CEILING:
        out.append(f"- To reach {_pct(targets.TARGET_CEILING)} of the ceiling on cornell_glass with the same rays, a "
                   f"pass has to fall from {ceil['pass_seconds'] * 1000:.1f} ms to "
                   f"{ceil['embree_seconds'] / targets.TARGET_CEILING * 1000:.1f} ms (2 threads, wall clock).")
    return "\n".join(out) if out else "- (no stage split in this run)"


def document(results, tables, plots, rel):
    cfg = results["config"]
    m = results["machine"]
    loads = ", ".join(f"{name} {load:.1f}" for name, load in m.get("load_by_section", []))
    parts = [
        "# Performance: speed against error",
        "",
        "Generated by `python -m benchmarks.run" + (" --quick" if cfg["quick"] else "") + f"` on "
        f"{results['started']} ({results['total_seconds']:.0f} s). Do not edit by hand: rerun the harness "
        "(`make bench`).",
        "",
        f"Machine: {m['cpu']}, {m['cores']} cores, Python {m['python']}; load average at start "
        f"{m['load_start'][0]:.1f}, at end {m['load_end'][0]:.1f} (other work on the machine slows every "
        "renderer alike; every comparison below is a ratio measured side by side in this run)."
        + (f" Load average at the start of each part: {loads}." if loads else ""),
        "",
        "## Targets",
        "",
        _targets(results),
        "",
        "## Reading the measurements",
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
        "sync, BVH, render). Each process is warmed up once first (imports, compiled kernels loaded), untimed.",
        f"- relMSE = mean((x - ref)^2 / (ref^2 + eps)) over pixels and RGB, eps = {cfg['relmse_epsilon']}, "
        "scene-linear Rec.709. FLIP = mean HDR-FLIP (flip-evaluator, 67 ppd). References: "
        f"{cfg['ref_spp']} spp for Prism unless a scene says otherwise (or {cfg['ref_max_seconds']:.0f} s, whichever "
        "first), cached in benchmarks/cache/ with their variance images; each table notes the reference's noise "
        "floor (expected relMSE contributed by the reference's own noise).",
        "- Peers run in their own processes with the same triangles, camera, light power and thread count: "
        "Mitsuba 3 `llvm_ad_spectral` (box filter, independent sampler, emitters hidden from the camera as "
        "Blender lights are) and Cycles through the bpy module on the CPU (no denoising, no adaptive sampling, "
        "its default 1.5 px Blackman-Harris filter). Each is scored against its own high-sample reference. "
        "On a scene with peers, Prism's default settings are rendered again until they have run as long "
        "as the slowest peer's longest render (spp doubling, at most 1/8 of the reference's spp), one "
        "repeat at a time, interleaved with the peers' repeats (peer processes of one repeat each), so a "
        "change in the machine's load falls on every side; the equal-time ratio is read at the longest time "
        "both curves measured, each interpolated log-log.",
        "- The sampler's gain: every scene also renders its default settings with `sampler=\"independent\"` "
        "(same seeds, same checkpoints, same reference as the Sobol default).",
        "",
        "## Ceiling: path throughput against bare embreex",
        "",
        "One pass's ray queries (`Accel.intersect`, `occluded`, `intersect_before` on the renderer's ray "
        "queues) are recorded on an untimed pass and replayed on a bare embreex scene of the renderer's own "
        "camera-relative triangles with the same thread count; renderer passes and replays alternate; "
        "fraction = embreex time / pass time (wall clock: the target). The CPU-time fraction divides the "
        "process CPU time of a replay by that of a pass: what each side costs in CPU, which other processes "
        "taking the cores do not change (idle threads and waits cost wall time, not CPU time).",
        "",
        _ceiling_table(results),
        "",
        "## Where a pass spends its time",
        "",
        "Each stage kernel of `engine/tracer/stages/trace.py` and each Embree query wrapped in a timer "
        "(`benchmarks/stage_split.py`, on passes of their own, never the timed ones): CPU milliseconds of the "
        f"calling thread per {cfg['pass_spp']}-spp pass, mean of {cfg['ceiling_passes']} passes, and the share "
        "of the CPU time of all chunks. CPU time is what a stage costs whatever else the machine runs; with "
        "two threads, a stage that costs more CPU than with one is slowed by the other thread (memory, "
        "caches). Light sampling (`nee.py`) and roulette run inside the shading kernel. The last row is the "
        "wall-clock side: threads x pass time not spent as CPU time in a chunk (idle threads, waiting for the "
        "last chunk, the pool, other processes on the machine). `film.add` runs on the main thread, outside "
        "the chunks.",
        "",
        "One thread:",
        "",
        _stage_table(results, 1),
        "",
        "Two threads (CPU time summed over both):",
        "",
        _stage_table(results, 2),
        "",
        "What dominates:",
        "",
        _dominates(results),
        "",
    ]
    sc = results.get("scaling")
    if sc:
        parts += ["## Thread scaling", "",
                  "Each case: renderer passes with T threads next to embreex replaying exactly the rays of one of "
                  "its passes with T threads, interleaved, medians of "
                  f"{sc['cases'][0]['rounds'] if sc['cases'] else 0} rounds (`benchmarks/scaling.py`).", "",
                  scaling_table(sc), ""]
    gains = results.get("sampler_gain")
    if gains:
        parts += ["## The sampler's gain at equal spp", "",
                  "relMSE of the default (Owen-scrambled Sobol) and of `sampler=\"independent\"`, medians over the "
                  "same seeds, against the same reference; FLIP beside it, since a few bright outliers (caustic "
                  "paths through glass) can decide relMSE at low spp.", "", _sampler_table(gains), ""]
    st = results.get("startup")
    if st:
        parts += ["## Cold compile and warm start", "",
                  f"`python -m benchmarks.startup`: a fresh process renders {st['scene']} at {st['resolution']} x "
                  f"{st['resolution']} (two 1-spp passes, 2 threads) with `PRISM_KERNEL_CACHE` pointing at an empty "
                  "folder (cold), then again with the kernels it left there (warm).", "", _startup_table(st), ""]
    demo = results.get("demo")
    if demo:
        parts += ["## The demo render", "",
                  f"`make render`'s scene and command (`render.py demo.blend --samples {demo['spp']}`, "
                  "480 x 320, all cores), each tree rendering its own build of the demo scene after an untimed "
                  "1-spp render, with seeds 0 and 1, the two trees taking turns (`benchmarks/demo.py`). Noise = "
                  "RMS difference of the two seeds' PNGs / sqrt 2, in 8-bit display levels: what a viewer sees "
                  "change from one seed to the next.", "", _demo_section(demo, rel), ""] + _demo_profile(demo)
    for name, table in tables.items():
        entry = results["scenes"][name]
        refs = ", ".join(f"{k}: {v['spp']} spp, {v['seconds']:.0f} s, noise floor {v['noise_floor']:.2g}"
                         for k, v in entry.get("references", {}).items())
        strategy = entry["strategies"][0]["strategy"]
        parts += [f"## {name}: {entry['description']}", "",
                  f"{entry['resolution']} x {entry['resolution']} pixels, checkpoints "
                  f"{', '.join(map(str, entry['checkpoints']))} spp, {entry['triangles']} triangles. Prism chose: "
                  f"`{strategy}`. References: {refs}.", ""]
        for peer in entry.get("peers", []):
            r = peer["reference"]
            parts.append(f"{peer['info']['renderer']} reference: {r['spp']} spp, noise floor "
                         f"{r['noise_floor']:.2g}; reference ratio peer/Prism (median over lit pixels) "
                         f"{peer['convention_ratio_median']:.3f}.")
            parts.append("")
        parts += [table, "", f"![{name}]({rel}/{name}.png)", ""]
    parts += ["## References", "", f"![references]({rel}/references.png)", ""]
    for record in results.get("experiments", []):
        parts += _experiment_section(record)
    if not results.get("experiments"):
        parts += ["## Experiments", "", "No modules in `benchmarks/experiments/` in this run.", ""]
    if results.get("errors"):
        parts += ["## Not measured in this run", ""] + [f"- {e}" for e in results["errors"]] + [""]
    return "\n".join(parts)
