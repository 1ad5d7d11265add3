"""Transparent Max Bounces side by side: docs/images/transparent_bounces.png.

    .venv/bin/python tools/transparent_bounces_picture.py [--samples 16]

Eight leaf-green cut-outs (Transparent BSDF, tint (0.85, 0.95, 0.75)), each smaller than the one under it, over an
emitter of radiance 1, seen from above at Max Bounces 0, rendered at Transparent Max Bounces 1, 3 and 8. A ray
through the middle crosses all eight; nearer the edge it crosses fewer. As in Cycles 4.5 a path makes at most
Transparent Max Bounces + 1 crossings, and the surface after its last one ends it: the middle goes black where
more layers lie than the setting allows. Before transparent bounces were counted apart (2026-12-07), every
crossing used one of Max Bounces, and at Max Bounces 0 all but the outer ring rendered black at any setting.
Prints the centre of each panel (eight layers), absolute: black where the setting allows fewer crossings; at 8,
the product of eight tint spectra, which is deeper than the product of eight RGB triples an RGB renderer forms.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests" / "tracer"))
OUTPUT = ROOT / "docs" / "images" / "transparent_bounces.png"
TINT = (0.85, 0.95, 0.75)
LAYERS = 8
SETTINGS = (1, 3, 8)
SIZE = 192


def _scene():
    from engine.tracer.bsdf.closure import TRANSPARENT
    from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
    from engine.tracer.scene import Camera, Material, SpectrumSpec, World
    from tracer_scenes import look_at, make_scene, quad

    cam = Camera("cam", look_at((0, 0, 30.0), (0, 0, 0), up=(0, 1, 0)), (SIZE, SIZE), focal_length_mm=50.0,
                 film_width_mm=36.0, film_height_mm=36.0)
    lamp = Material("lamp", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    leaf = Material("leaf", shader=ShaderProgram([ClosureSpec(TRANSPARENT, tint=Colour(rgb=TINT))]))
    parts = [(*quad((0, 0, 0), (20, 0, 0), (0, 20, 0)), 0)]
    for k in range(LAYERS):  # layer k at z = 1 + k, half-width shrinking by 1 m per layer
        half = 10.0 - k
        parts.append((*quad((0, 0, 1.0 + k), (half, 0, 0), (0, half, 0)), 1))
    return make_scene(parts, [lamp, leaf], cam, [], World(color=(0.0, 0.0, 0.0), strength=0.0))


def _render(samples, transparent_max_bounces):
    from engine.tracer.renderer import Renderer
    from engine.tracer.settings import RenderSettings

    settings = RenderSettings(samples=samples, samples_per_pass=samples, max_bounces=0, seed=1,
                              transparent_max_bounces=transparent_max_bounces, russian_roulette_depth=64)
    with Renderer(_scene(), settings) as r:
        r.render_pass()
        return np.asarray(r.image_rgb(), np.float64)


def _display(rgb):
    linear = np.clip(rgb, 0.0, 1.0)
    srgb = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    return (srgb * 255 + 0.5).astype(np.uint8)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=16)
    args = parser.parse_args()
    from PIL import Image, ImageDraw

    panels = []
    for setting in SETTINGS:
        rgb = _render(args.samples, setting)
        centre = rgb[SIZE // 2 - 4:SIZE // 2 + 4, SIZE // 2 - 4:SIZE // 2 + 4].mean((0, 1))
        why = (f"{LAYERS} layers are more than {setting} + 1 crossings" if setting + 1 < LAYERS else
               f"an RGB renderer's tint^{LAYERS} is {np.round(np.array(TINT) ** LAYERS, 4).tolist()}: Prism "
               "multiplies the tint's spectra")
        print(f"MEASURED Transparent Max Bounces {setting}: centre {np.round(centre, 4).tolist()} ({why})")
        panels.append((setting, Image.fromarray(_display(rgb))))
    band = 18  # a caption under each panel
    picture = Image.new("RGB", (SIZE * len(panels) + 4 * (len(panels) - 1), SIZE + band), (255, 255, 255))
    draw = ImageDraw.Draw(picture)
    for n, (setting, panel) in enumerate(panels):
        picture.paste(panel, (n * (SIZE + 4), 0))
        draw.text((n * (SIZE + 4) + 6, SIZE + 4), f"Transparent Max Bounces {setting}", fill=(0, 0, 0))
    picture.save(OUTPUT, optimize=True)
    print(f"wrote {OUTPUT}")


if __name__ == "__main__":
    main()
