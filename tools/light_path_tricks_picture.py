"""The demo scene rendered as Prism renders it by default (unbiased) and with Cycles' own Light Paths
defaults asked for (Clamp Indirect 10, Filter Glossy 1), side by side: docs/images/light_path_tricks_demo.png.

    .venv/bin/python tools/light_path_tricks_picture.py [--samples 64]

Builds ``renders/demo.blend`` (``demo/build_demo_scene.py``) when it is missing, saves a copy with the two
settings set on ``scene.cycles`` (Prism reads only values a scene has set), renders both with ``render.py``
and prints each image's mean and its share of fireflies (``_fireflies``).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
PYTHON = sys.executable
OUTPUT = ROOT / "docs" / "images" / "light_path_tricks_demo.png"
_SET_TRICKS = """
import bpy, sys
bpy.ops.wm.open_mainfile(filepath=sys.argv[-2])
cycles = bpy.context.scene.cycles
cycles.sample_clamp_indirect = 10.0
cycles.blur_glossy = 1.0
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[-1])
"""


def _render(blend: Path, output: Path, samples: int) -> np.ndarray:
    subprocess.run([PYTHON, str(ROOT / "render.py"), str(blend), "--samples", str(samples), "--seed", "0",
                    "--output", str(output)], check=True, cwd=ROOT)
    return np.asarray(Image.open(output).convert("RGB"), np.float64) / 255.0


def _fireflies(image: np.ndarray) -> float:
    """The share of pixels brighter than the median of their 3 × 3 neighbourhood by more than a tenth of the
    display range: isolated bright dots."""
    lum = image @ np.array([0.2126, 0.7152, 0.0722])
    padded = np.pad(lum, 1, mode="edge")
    h, w = lum.shape
    around = np.stack([padded[y:y + h, x:x + w] for y in range(3) for x in range(3)])
    return float((lum - np.median(around, axis=0) > 0.1).mean())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=64)
    arguments = parser.parse_args()
    demo = ROOT / "renders" / "demo.blend"
    if not demo.exists():
        subprocess.run([PYTHON, str(ROOT / "demo" / "build_demo_scene.py"), str(demo)], check=True, cwd=ROOT)
    with tempfile.TemporaryDirectory() as folder:
        tricks = Path(folder) / "demo_cycles_defaults.blend"
        subprocess.run([PYTHON, "-c", _SET_TRICKS, str(demo), str(tricks)], check=True, cwd=ROOT)
        before = _render(demo, Path(folder) / "unbiased.png", arguments.samples)
        after = _render(tricks, Path(folder) / "tricks.png", arguments.samples)
    for name, image in (("unbiased (Prism's default)", before), ("Clamp Indirect 10, Filter Glossy 1", after)):
        print(f"{name}: mean {image.mean():.4f} (display levels 0-1), fireflies {100 * _fireflies(image):.2f} % of "
              "pixels")
    seam = np.ones((before.shape[0], 4, 3))
    picture = (np.concatenate([before, seam, after], axis=1) * 255.0 + 0.5).astype(np.uint8)
    OUTPUT.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(picture).save(OUTPUT, optimize=True)
    print(f"wrote {OUTPUT}")


if __name__ == "__main__":
    main()
