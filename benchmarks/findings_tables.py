"""The Markdown tables of docs/performance.md: the ceiling, the stage split, thread scaling, the
sampler's gain, cold compile and warm start, the demo render (and its scene's stage split), and one
section per experiment. ``findings.document`` places them; every number comes from ``results``.
"""

from __future__ import annotations

import numpy as np

from .findings_values import _pct


def _ceiling_table(results):
    rows = ["| scene | threads | pass (s), median | embreex on the same rays (s) | fraction | fraction in CPU time | "
            "samples/s | ceiling samples/s | rays recorded (closest / shadow / film) | rays in stats |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for c in results.get("ceiling", []):
        rows.append(f"| {c['scene']} | {c['threads']} | {c['pass_seconds']:.4f} | {c['embree_seconds']:.4f} | "
                    f"{_pct(c['fraction'])} | {_pct(c.get('cpu_fraction'))} | "
                    f"{c['samples_per_second']:,.0f} | {c['ceiling_samples_per_second']:,.0f} | "
                    f"{c['rays_recorded']:,} ({c['closest_rays']:,} / {c['shadow_rays']:,} / {c['film_rays']:,}) | "
                    f"{c['rays_counted']:,} |")
    return "\n".join(rows)


def _stage_table(results, threads):
    entries = [(s["scene"], s[str(threads)]) for s in results.get("stages", []) if str(threads) in s]
    if not entries:
        return "(not measured)"
    stages = []  # every scene's stages, each new one placed after the stage it follows in its scene
    for _, split in entries:
        previous = None
        for r in split["rows"]:
            if r["stage"] not in stages:
                stages.insert(stages.index(previous) + 1 if previous in stages else len(stages), r["stage"])
            previous = r["stage"]
    rows = ["| CPU ms per pass (share of the chunks' CPU) | " + " | ".join(name for name, _ in entries) + " |",
            "|---|" + "---:|" * len(entries),
            "| pass, wall clock | " + " | ".join(f"{1000 * split['pass_seconds']:.1f}" for _, split in entries) + " |",
            "| all chunks, CPU | " + " | ".join(f"{1000 * split['chunk_cpu']:.1f}" for _, split in entries) + " |"]
    for stage in stages:
        cells = []
        for _, split in entries:
            row = next((r for r in split["rows"] if r["stage"] == stage), None)
            share = "" if row is None or not np.isfinite(row["share"]) else f" ({_pct(row['share'])})"
            cells.append("-" if row is None else f"{1000 * row['cpu']:.1f}{share}")
        rows.append(f"| {stage} | " + " | ".join(cells) + " |")
    rows.append(f"| {threads} x wall - chunks' CPU (idle, waits, descheduled) | "
                + " | ".join(f"{1000 * split['unexplained']:.1f}" for _, split in entries) + " |")
    return "\n".join(rows)


def _sampler_table(gains):
    rows = ["| scene | spp | relMSE Sobol | relMSE independent | independent / Sobol | FLIP Sobol | FLIP independent |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for g in gains:
        for p in g["points"]:
            rows.append(f"| {g['scene']} | {p['spp']} | {p['sobol']:.3g} | {p['independent']:.3g} | {p['gain']:.2f} | "
                        f"{p['flip_sobol']:.3f} | {p['flip_independent']:.3f} |")
    return "\n".join(rows)


def _startup_table(st):
    keys = [("process_seconds", "whole process (interpreter start-up included)"),
            ("import_seconds", "import the tracer (numba, kernel modules)"),
            ("setup_seconds", "Renderer construction (spectral tables, BVH)"),
            ("first_pass_seconds", "first pass (compile, or load the kernels from disk)"),
            ("second_pass_seconds", "second pass"),
            ("compile_seconds", "compiling, in the phases above (numba's front end and LLVM)"),
            ("llvm_seconds", "of it in LLVM (optimising, machine code; warm: loading it)")]
    rows = ["| phase | cold cache (s) | warm cache (s) |", "|---|---:|---:|"]
    for key, label in keys:
        rows.append(f"| {label} | {st['cold'].get(key, float('nan')):.3f} | {st['warm'].get(key, float('nan')):.3f} |")
    rows.append("| numba functions compiled | " + " | ".join(
        str(st[side].get("functions_compiled", "-")) for side in ("cold", "warm")) + " |")
    rows.append("| imported colour-science | " + " | ".join(
        "yes" if st[side].get("colour_imported", True) else "no" for side in ("cold", "warm")) + " |")
    return "\n".join(rows)


def _demo_section(demo, rel):
    before = demo.get("before", {})
    def noise(side):
        return f"{side['noise']:.2f}" if "noise" in side else "-"

    lines = ["| | process (s), mean [runs] | Blender render time (s) | noise (display levels) | image |",
             "|---|---:|---:|---:|---|"]
    for label, side, alt in ((f"numpy tracer ({demo['before_commit'][:7]})", before, "before"),
                             ("compiled core", demo["now"], "now")):
        if "process_seconds" in side:
            runs = ", ".join(f"{t:.1f}" for t in side.get("runs", []))
            lines.append(f"| {label} | {side['process_seconds']:.1f} [{runs}] | {side['blender_seconds']:.1f} | "
                         f"{noise(side)} | ![{alt}]({rel}/{side['image']}) |")
    return "\n".join(lines)


def _demo_profile(demo):
    """Where the demo scene's pass goes (its stage split), or a note."""
    prof = demo.get("profile")
    if not prof:
        return []
    if "error" in prof:
        return [f"The demo scene's profile failed in this run ({prof['error']}).", ""]
    split = prof["stages"]
    lines = [f"Where a pass of the demo scene goes (`tools/profile_pass.py --blend demo.blend --spp {prof['spp']}`, "
             f"{prof['width']} x {prof['height']}, {prof['triangles']:,} triangles, {prof['threads']} threads): "
             f"{prof['rays'] / prof['paths']:.2f} rays per path, {1e6 * split['chunk_cpu'] / split['paths']:.2f} "
             f"CPU-us per path in the chunks, {_pct(prof.get('fraction'))} of the embreex ceiling "
             f"({_pct(prof.get('cpu_fraction'))} in CPU time).", "",
             "| stage | CPU ms per pass | share |", "|---|---:|---:|"]
    for row in split["rows"]:
        if np.isfinite(row["share"]):
            lines.append(f"| {row['stage']} | {1000 * row['cpu']:.1f} | {_pct(row['share'])} |")
    return lines + [""]


def _cell(value):
    if isinstance(value, float):
        return "n/a" if not np.isfinite(value) else f"{value:.3g}"
    return str(value).replace("|", "\\|").replace("\n", " ")


def _experiment_section(record):
    parts = [f"## Experiment: {record['title']}", ""]
    if "error" in record:
        parts += [f"Skipped: `benchmarks/experiments/{record['name']}.py` failed in this run "
                  f"({_cell(record['error'])}).", ""]
        return parts
    if record.get("summary"):
        parts += [record["summary"], ""]
    rows = record.get("rows", [])
    columns = []
    for row in rows:
        columns += [k for k in row if k not in columns]
    if columns:
        parts += ["| " + " | ".join(_cell(c) for c in columns) + " |", "|" + "---|" * len(columns)]
        parts += ["| " + " | ".join(_cell(row[c]) if c in row else "" for c in columns) + " |" for row in rows]
        parts.append("")
    parts += [f"(`benchmarks/experiments/{record['name']}.py`, {record['seconds']:.1f} s)", ""]
    return parts
