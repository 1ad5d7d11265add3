"""Where a render's CPU time goes, function by function, compiled kernels included (Linux ``perf``).

    .venv/bin/python tools/perf_kernels.py cornell_glass [--size 64] [--spp 16] [--threads 1] [--seconds 20]
    .venv/bin/python tools/perf_kernels.py --blend renders/demo.blend [--spp 4] ...   (bpy module)
    .venv/bin/python tools/perf_kernels.py cornell_glass --annotate shade_kernel   (its hottest instructions)
    .venv/bin/python tools/perf_kernels.py cornell_grey --cycles   (Cycles on the same scene, for comparison)

``perf`` sees numba's machine code as anonymous memory. This tool compiles the kernels afresh into a
throw-away cache (the LLVM modules, and so the function names, exist only for code compiled in this
process: ~2 minutes), writes ``/tmp/perf-<pid>.map`` (start, size, name of every compiled function,
sizes up to the next function's start), then lets ``perf record`` sample the process while it renders
passes, and prints the share of samples per shared library and per function. Functions numba inlined
are counted in their caller (most of shading is in ``shade_kernel`` itself). Needs ``perf`` and
``kernel.perf_event_paranoid`` <= 2.
"""

from __future__ import annotations

import argparse
import ctypes
import gc
import importlib
import os
import shutil
import subprocess
import sys
import tempfile
import threading
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def _demangle(symbol: str) -> str:
    """numba's Itanium-style name (``_ZN6engine6tracer...``) as a dotted Python path."""
    if not symbol.startswith("_ZN"):
        return symbol
    parts, i = [], 3
    while i < len(symbol) and symbol[i].isdigit():
        j = i
        while symbol[j].isdigit():
            j += 1
        length = int(symbol[i:j])
        parts.append(symbol[j:j + length])
        i = j + length
    return ".".join(parts) or symbol


def write_perf_map(path: Path) -> dict[str, tuple[int, int]]:
    """Write the perf map of every function compiled in this process; returns name -> (start, size)."""
    from numba.core.registry import CPUDispatcher

    starts = {}
    for obj in gc.get_objects():
        if not isinstance(obj, CPUDispatcher):
            continue
        for result in obj.overloads.values():
            library = result.library
            for function in library._final_module.functions:
                if function.is_declaration:
                    continue
                try:
                    address = library.get_pointer_to_function(function.name)
                except Exception:  # noqa: BLE001 - dropped by the optimiser: nothing to map
                    continue
                if address:
                    starts[address] = _demangle(function.name)
    ordered = sorted(starts)
    spans = {}
    with open(path, "w", encoding="utf-8") as out:
        for start, end in zip(ordered, ordered[1:] + [ordered[-1] + 65536] if ordered else []):
            size = min(end - start, 1 << 20)
            out.write(f"{start:x} {size:x} {starts[start]}\n")
            spans[starts[start]] = (start, size)
    return spans


def annotate(data: Path, spans: dict, name_part: str, folder: Path, lines: int = 60) -> None:
    """The hottest instructions of the function whose name contains ``name_part``: its machine code is
    read from this process's memory and disassembled, the samples' addresses counted against it."""
    matches = [name for name in spans if name_part in name]
    if not matches:
        print(f"no compiled function's name contains {name_part!r}")
        return
    name = min(matches, key=len)
    start, size = spans[name]
    code = folder / "function.bin"
    code.write_bytes(ctypes.string_at(start, size))
    listing = subprocess.run(["objdump", "-D", "-b", "binary", "-m", "i386:x86-64", "--no-show-raw-insn",
                              f"--adjust-vma={start:#x}", str(code)], capture_output=True, text=True).stdout
    ips = subprocess.run(["perf", "script", "-i", str(data), "-F", "ip"], capture_output=True, text=True).stdout
    addresses = (int(ip, 16) for ip in ips.split())
    counts = Counter(at for at in addresses if start <= at < start + size)
    total = sum(counts.values()) or 1
    print(f"{name}: {total} samples in {size} bytes; hottest instructions (share of the function):")
    rows = []
    for line in listing.splitlines():
        address, sep, text = line.partition(":")
        try:
            at = int(address.strip(), 16)
        except ValueError:
            continue
        if sep and text.strip():
            rows.append((at, text.strip()))
    hot = sorted(rows, key=lambda row: -counts.get(row[0], 0))[:lines]
    for at, text in sorted(hot):
        print(f"  {100.0 * counts.get(at, 0) / total:5.1f} %  {at - start:6x}  {text[:90]}")


def _report(data: Path, top: int) -> None:
    def table(sort):
        text = subprocess.run(["perf", "report", "-i", str(data), "--sort", sort, "--stdio", "--percent-limit", "0.2"],
                              capture_output=True, text=True).stdout
        return [line for line in text.splitlines() if line.strip() and not line.startswith("#")]

    print("share of samples per library:")
    libraries = table("dso")
    for line in libraries[:12]:
        print("  " + line.strip())
    shares = {line.split("%", 1)[1].strip(): float(line.split("%", 1)[0]) for line in libraries}
    # Cycles' idle TBB workers yield in a loop: kernel and TBB samples that render nothing.
    idle = sum(share for name, share in shares.items() if "kernel.kallsyms" in name or "libtbb" in name)
    embree = sum(share for name, share in shares.items() if "embree" in name)
    print(f"Embree's share of the user-space samples (the OS kernel and TBB left out): "
          f"{100.0 * embree / max(100.0 - idle, 1e-9):.1f} %")
    print("per function (numba's by module path; Embree's library is stripped):")
    rows = []
    for line in table("sym"):
        share, _, rest = line.strip().partition("%")
        name = rest.split("]", 1)[-1].strip()
        rows.append((float(share), _demangle(name)))
    for share, name in rows[:top]:
        print(f"  {share:6.2f} %  {name[:110]}")


def _record_while(data: Path, seconds: float, render) -> int:
    """Call ``render()`` over and over while ``perf record`` samples this process for ``seconds``;
    returns how many calls ran."""
    record = subprocess.Popen(["perf", "record", "-q", "-p", str(os.getpid()), "-o", str(data), "--",
                               "sleep", str(seconds)])
    done = threading.Event()
    threading.Thread(target=lambda: (record.wait(), done.set()), daemon=True).start()
    calls = 0
    while not done.is_set():
        render()
        calls += 1
    return calls


def profile_cycles(args, folder: Path) -> None:
    """The same scene rendered by Cycles (``benchmarks.peers.cycles``: CPU, Embree in its own library,
    ``--threads`` threads), sampled the same way: Embree's share of a renderer that is not Prism."""
    import bpy

    from benchmarks import scenes
    from benchmarks.peers.cycles import build_blender_scene

    blender = build_blender_scene(scenes.build(args.scene, (args.size, args.size)), args.threads)
    blender.render.filepath = str(folder / "cycles.exr")
    blender.cycles.samples = args.spp
    blender.render.use_persistent_data = True  # later renders reuse the BVH: traversal is measured, not builds
    bpy.ops.render.render(write_still=True)  # kernels loaded, scene synchronised
    data = folder / "perf.data"
    renders = _record_while(data, args.seconds, lambda: bpy.ops.render.render(write_still=True))
    print(f"Cycles: {renders} renders of {args.spp} spp, {args.threads} thread(s)")
    _report(data, args.top)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", nargs="?", default="cornell_glass")
    parser.add_argument("--blend")
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--top", type=int, default=30)
    parser.add_argument("--annotate", metavar="NAME", help="also list the hottest instructions of this function")
    parser.add_argument("--cycles", action="store_true", help="profile Cycles rendering the benchmark scene instead")
    args = parser.parse_args(argv)
    cache = tempfile.mkdtemp(prefix="prism-perf-kernels-")
    if args.cycles:
        profile_cycles(args, Path(cache))
        shutil.rmtree(cache, ignore_errors=True)
        return 0
    os.environ["PRISM_KERNEL_CACHE"] = cache  # before any kernel module is imported: compile here

    from dataclasses import replace

    if args.blend:
        from tools.profile_pass import _blend

        scene, settings = _blend(args.blend, args)
        renderer_module = importlib.import_module(type(scene).__module__.rsplit(".", 1)[0] + ".renderer")
    else:
        from benchmarks import prism_runs, scenes
        from engine.tracer import renderer as renderer_module

        scene = scenes.build(args.scene, (args.size, args.size))
        settings = replace(prism_runs.settings_for({}, samples=10**6, seed=args.seed, threads=args.threads),
                           samples_per_pass=args.spp)
    data = Path(cache) / "perf.data"
    with renderer_module.Renderer(scene, settings) as renderer:
        renderer.render_pass()  # compiles every kernel the scene uses
        spans = write_perf_map(Path(f"/tmp/perf-{os.getpid()}.map"))
        print(f"{len(spans)} compiled functions mapped; sampling {args.seconds:g} s of passes", flush=True)
        passes = _record_while(data, args.seconds, renderer.render_pass)
    print(f"{passes} passes of {settings.samples_per_pass} spp, {args.threads} thread(s)")
    _report(data, args.top)
    if args.annotate:
        annotate(data, spans, args.annotate, Path(cache))
    shutil.rmtree(cache, ignore_errors=True)  # the throw-away kernels (~100 MB) and perf's samples
    return 0


if __name__ == "__main__":
    sys.exit(main())
