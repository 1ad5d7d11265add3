"""``python -m benchmarks.parity.run`` (``make parity``): compare every parity scene (or ``--scenes``),
write the side-by-side pictures to docs/images/parity/ and the report to docs/parity.md.

``--seeds K`` (K > 1) also renders each scene with K seeds per engine to measure the noise of its ratio.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]


def _arguments(argv):
    parser = argparse.ArgumentParser(prog="python -m benchmarks.parity.run", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", nargs="*", help="names of the scenes to compare (default: all)")
    parser.add_argument("--seeds", type=int, default=1, help="seeds per engine for the noise study (1: none)")
    parser.add_argument("--docs", type=Path, default=REPOSITORY / "docs", help="the docs folder to write into")
    return parser.parse_args(argv)


def main(argv) -> int:
    arguments = _arguments(argv)
    import bpy

    from render import prism_package_name

    from .catalogue import SCENES, scene_named
    from .compare import compare
    from .noise import estimate_noise
    from .report import write_report

    prism_package_name()  # registers this checkout's add-on
    scenes = [scene_named(name) for name in arguments.scenes] if arguments.scenes else SCENES
    pictures = arguments.docs / "images" / "parity"
    results, noise = [], {}
    for scene in scenes:
        started = time.perf_counter()
        result = compare(scene, picture=pictures / f"{scene.name}.png", docs=arguments.docs)
        results.append(result)
        ratio = "—" if result.ratio is None else f"{result.ratio:.4f}"
        print(f"{scene.name:24s} ratio {ratio}  verdict {result.verdict:9s} {time.perf_counter() - started:5.1f} s",
              flush=True)
        if arguments.seeds > 1 and scene.expected_warning is None:
            estimate = estimate_noise(scene, arguments.seeds)
            if estimate is not None:
                noise[scene.name] = estimate
                print(f"{'':24s} ratio σ {estimate.ratio_spread:.2%} over {arguments.seeds} seeds", flush=True)
    write_report(arguments.docs / "parity.md", results, noise, bpy.app.version_string)
    print(f"wrote {arguments.docs / 'parity.md'}", flush=True)
    return 0 if all(r.verdict in ("match", "warned") or r.scene.known_difference for r in results) else 1


if __name__ == "__main__":
    sys.path.insert(0, str(REPOSITORY))
    from render import exit_now  # the bpy module can hang at interpreter exit

    exit_now(main(sys.argv[1:]))
