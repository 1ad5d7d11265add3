"""The warm-up process: compile the tracer's kernels into the cache, then mark it warm.

    <python> child.py --package bl_ext.user_default.prism_spectral --root <add-on folder> \\
        --cache <kernel cache directory> --lock <lock file> [--cpu-target x86-64-v3]

Run as a script by ``launch.start`` with ``sys.executable`` (Blender's bundled Python, or the tests'); the
add-on never imports it. numba's cache index is per module name (``engine.tracer.kernel_folder``), so the tracer
is imported under the parent's package name: the packages on the way (``bl_ext``,
``bl_ext.user_default``, ``...prism_spectral``) are recreated as plain modules whose ``__path__`` leads to
the add-on's folder, so the add-on's ``__init__`` (which imports bpy) never runs; ``engine`` and
``engine.tracer`` import nothing themselves. It renders ``scene.warmup_scene()`` at low priority, one
thread, runs the export's constant folder (``scene.fold_once``), then ``jit.mark_cache_warm()``. Its
output is the log next to the lock; it removes the lock last.

A killed warm-up leaves no state a render trips on: numba writes each cache file to a temporary name
and renames it into place (a render finds a kernel whole or not at all, and compiles what is missing),
and the cache is only marked warm after the render finished.
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import sys
import time
import types


def adopt_package(package: str, root: str) -> None:
    """Make ``package`` (dotted) importable as the add-on folder ``root`` without running its ``__init__``."""
    if not package:
        sys.path.insert(0, root)  # the tracer as plain ``engine.tracer`` (tools, tests)
        return
    parts = package.split(".")
    for depth in range(1, len(parts) + 1):
        name = ".".join(parts[:depth])
        module = sys.modules.get(name)
        if module is None:
            module = types.ModuleType(name)
            module.__path__ = [root] if depth == len(parts) else []
            sys.modules[name] = module
            if depth > 1:
                setattr(sys.modules[".".join(parts[: depth - 1])], parts[depth - 1], module)


def compile_counter():
    """A list that numba's compile events append to (one entry per function compiled, not loaded); the
    install check (``tools/check_extension_install.py``) counts a render's compiles with it too."""
    from numba.core import event

    compiled = []

    class Count(event.Listener):
        def on_start(self, data):
            pass

        def on_end(self, data):
            compiled.append(data)

    event.register("numba:compile", Count())
    return compiled


def warm_up(package: str, cache: str, cpu_target: str | None = None) -> dict:
    """Import the tracer as ``package``, render the warm-up scene into ``cache`` with kernels compiled for
    ``cpu_target`` (None: this machine's CPU; see ``engine.tracer.kernel_target``); what it did, in seconds."""
    sys.modules.setdefault("matplotlib", None)  # as in Blender: colour-science skips it (~1 s) when absent
    prefix = f"{package}." if package else ""
    start = time.perf_counter()
    importlib.import_module(f"{prefix}engine.tracer.kernel_target").use(cpu_target)
    jit = importlib.import_module(f"{prefix}engine.tracer.jit")
    jit.configure_cache(cache)
    if jit.cache_is_warm():
        return {"already_warm": True, "kernel_directory": str(jit.kernel_directory())}
    compiled = compile_counter()
    renderer = importlib.import_module(f"{prefix}engine.tracer.renderer")
    settings = importlib.import_module(f"{prefix}engine.tracer.settings")
    work = importlib.import_module(f"{prefix}engine.warmup.scene")
    with renderer.Renderer(work.warmup_scene(), settings.RenderSettings(samples=1, samples_per_pass=1, seed=0,
                                                                       threads=1)) as r:
        r.render_pass()
    work.fold_once()
    jit.mark_cache_warm()
    return {"already_warm": False, "kernel_directory": str(jit.kernel_directory()),
            "numba_directory": str(jit.numba_directory()),
            "functions_compiled": len(compiled), "seconds": round(time.perf_counter() - start, 1)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--package", required=True, help="the parent's add-on package name ('' for engine.tracer)")
    parser.add_argument("--root", required=True, help="the add-on's folder")
    parser.add_argument("--cache", required=True, help="the kernel cache directory the parent configured")
    parser.add_argument("--lock", help="the lock file to remove at the end")
    parser.add_argument("--cpu-target", help="compile for this portable CPU level (default: this machine's CPU)")
    args = parser.parse_args(argv)
    if hasattr(os, "nice"):
        try:
            os.nice(10)  # lowest priority but one: Blender and the user's work come first
        except OSError:
            pass
    adopt_package(args.package, args.root)
    lock = importlib.import_module(f"{args.package + '.' if args.package else ''}engine.warmup.lock")
    status = 1
    try:
        print(f"Prism kernel warm-up, pid {os.getpid()}, package {args.package or 'engine'}, cache {args.cache}",
              flush=True)
        done = warm_up(args.package, args.cache, args.cpu_target)
        print(f"Prism kernel warm-up done: {json.dumps(done)}", flush=True)
        status = 0
    except BaseException:  # noqa: BLE001 - the log says what went wrong; the lock must go in any case
        import traceback

        traceback.print_exc()
    finally:
        if args.lock:
            from pathlib import Path

            lock.release(Path(args.lock), os.getpid())
    return status


if __name__ == "__main__":
    del sys.path[0]  # this folder (engine/warmup): its modules must only be imported through the package
    sys.exit(main())
