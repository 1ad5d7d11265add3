"""Where a cold compile of the kernels goes: seconds per compiled function, for a small render.

    .venv/bin/python tools/compile_profile.py [cornell_glass] [--top 25]

Points ``PRISM_KERNEL_CACHE`` at a new empty folder, renders one pass of a 16x16 benchmark scene and
records numba's compile events (``numba.core.event``). A function's compile includes those of the
functions it calls for the first time (nested events), so both its own ("self") seconds and its
inclusive seconds are printed, largest self time first.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", nargs="?", default="cornell_glass")
    parser.add_argument("--top", type=int, default=25)
    args = parser.parse_args(argv)
    cache = tempfile.mkdtemp(prefix="prism-compile-profile-")
    os.environ["PRISM_KERNEL_CACHE"] = cache
    from numba.core import event

    events = []

    class Listener(event.Listener):
        def on_start(self, ev):
            events.append(("start", ev.data["dispatcher"].py_func.__qualname__, ev.data["args"], time.perf_counter()))

        def on_end(self, ev):
            events.append(("end", ev.data["dispatcher"].py_func.__qualname__, ev.data["args"], time.perf_counter()))

    event.register("numba:compile", Listener())
    start = time.perf_counter()
    from benchmarks import scenes
    from engine.tracer.renderer import Renderer
    from engine.tracer.settings import RenderSettings

    with Renderer(scenes.build(args.scene, (16, 16)), RenderSettings(samples=1, samples_per_pass=1, seed=0,
                                                                      threads=1)) as renderer:
        renderer.render_pass()
    total = time.perf_counter() - start
    inclusive, own, count = defaultdict(float), defaultdict(float), defaultdict(int)
    stack = []
    for kind, name, _, at in events:
        if kind == "start":
            stack.append([name, at, 0.0])
        else:
            entry = stack.pop()
            spent = at - entry[1]
            inclusive[name] += spent
            own[name] += spent - entry[2]
            count[name] += 1
            if stack:
                stack[-1][2] += spent
    print(f"{args.scene} 16x16, one pass, cold cache: {total:.1f} s in all, {sum(own.values()):.1f} s compiling "
          f"{sum(count.values())} signatures of {len(count)} functions")
    print(f"{'function':60s} {'self s':>8s} {'incl. s':>8s} {'sigs':>5s}")
    for name in sorted(own, key=own.get, reverse=True)[:args.top]:
        print(f"{name:60s} {own[name]:8.2f} {inclusive[name]:8.2f} {count[name]:5d}")
    # A function compiled for several signatures pays for each: show where they differ.
    signatures = defaultdict(list)
    for kind, name, types, _ in events:
        if kind == "start":
            signatures[name].append(tuple(types))
    for name in sorted(own, key=own.get, reverse=True)[:args.top]:
        found = signatures[name]
        if len(found) > 1 and own[name] > 1.0:
            differing = [i for i in range(len(found[0])) if len({str(s[i]) if i < len(s) else "" for s in found}) > 1]
            print(f"{name}: {len(found)} signatures, differing in arguments {differing}:")
            for s in found:
                print("   ", [str(s[i]) for i in differing if i < len(s)])
    import shutil

    shutil.rmtree(cache, ignore_errors=True)
    return 0


if __name__ == "__main__":
    from engine.batch.process_exit import exit_now

    exit_now(main())
