"""Metamerism, rendered by Prism: two paints that match in daylight and part under a shop's light.

    .venv/bin/python demo/metamerism.py docs/images/metamerism.png

Left: the measured reflectance of the ColorChecker's orange-yellow patch (colour-science's
``SDS_COLOURCHECKERS``). Right: a paint mixed from three primaries to match it under D65 (the
reflectance colour-science's ``XYZ_to_sd(..., method="Mallett 2019")`` gives for the patch's D65
colour). Top row lit by D65, bottom row by FL11, a tri-band fluorescent tube; both lamps have the same
luminance and the image is not white-balanced. An RGB renderer multiplies the same three numbers under
any light, so it cannot show the split.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from engine.tracer.renderer import Renderer  # noqa: E402
from engine.tracer.scene import (Camera, Light, Material, ReflectanceSpec, SampledSpectrum, Scene,  # noqa: E402
                                 SpectrumSpec)
from engine.tracer.settings import RenderSettings  # noqa: E402
from engine.tracer.spectra import cie  # noqa: E402
from engine.tracer.spectra.reflectance_spectrum import ReflectanceSpectrum  # noqa: E402

PATCH = "ColorChecker N Ohta: orange yellow"
LIGHTS = ("D65", "FL11")
BACKDROP_GREY = 0.18


def metamer_pair() -> tuple[ReflectanceSpec, ReflectanceSpec]:
    """(the measured patch, the three-primary paint that matches it under D65)."""
    colour = cie.import_colour()
    measured = ReflectanceSpec(kind="measured", name=PATCH)
    grid = np.arange(360.0, 831.0)
    reflectance = ReflectanceSpectrum(measured).evaluate(grid)
    d65 = colour.SDS_ILLUMINANTS["D65"]
    patch = colour.SpectralDistribution(dict(zip(grid.tolist(), reflectance.tolist())))
    xyz = colour.sd_to_XYZ(patch, illuminant=d65) / 100.0
    mixed = colour.XYZ_to_sd(xyz, method="Mallett 2019")
    values = np.clip(mixed.values, 0.0, 1.0)  # a mixture of reflectances: within 0-1 up to rounding
    table = SampledSpectrum(tuple(float(w) for w in mixed.wavelengths), tuple(float(v) for v in values),
                            "three-primary paint (Mallett 2019)")
    return measured, ReflectanceSpec(kind="tabulated", table=table)


def _quad(x0, x1, y0, y1, z=0.0):
    vertices = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]], dtype=np.float64)
    return vertices, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32)


def scene(illuminant: str, resolution=(320, 160)) -> Scene:
    """The two paints side by side on a grey card, under a large area lamp emitting ``illuminant``."""
    measured, mixed = metamer_pair()
    parts = [_quad(-1.0, 0.0, -0.5, 0.5, 0.001), _quad(0.0, 1.0, -0.5, 0.5, 0.001), _quad(-3.0, 3.0, -3.0, 3.0)]
    vertices = np.concatenate([v for v, _ in parts])
    triangles = np.concatenate([t + 4 * i for i, (_, t) in enumerate(parts)])
    camera_to_world = np.eye(4)
    camera_to_world[:3, 3] = (0.0, 0.0, 3.0)  # looking down -Z, +Y up
    view_width_m = 2.4
    camera = Camera("Camera", camera_to_world, resolution, focal_length_mm=36.0 * 3.0 / view_width_m,
                    film_width_mm=36.0, film_height_mm=36.0 * resolution[1] / resolution[0])
    lamp = Light("Lamp", "area", np.array([0.0, 0.0, 4.0]), size_u_m=6.0, size_v_m=6.0, power_w=400.0,
                 spectrum=SpectrumSpec(kind="illuminant", illuminant=illuminant))
    materials = [Material("measured", reflectance=measured), Material("mixed", reflectance=mixed),
                 Material("card", base_color=(BACKDROP_GREY,) * 3)]
    return Scene(vertices, triangles, np.array([0, 0, 1, 1, 2, 2], np.int32), materials, camera, [lamp])


def render(illuminant: str, resolution=(320, 160), samples=64, seed=0) -> np.ndarray:
    """Scene-linear Rec.709 [H, W, 3] of the pair under ``illuminant``."""
    settings = RenderSettings(samples=samples, samples_per_pass=samples, seed=seed, max_bounces=2)
    with Renderer(scene(illuminant, resolution), settings) as renderer:
        renderer.render_pass()
        return renderer.image_rgb().astype(np.float64)


def patch_colours(image) -> np.ndarray:
    """Mean colour [2, 3] of the middle of the left and right paint."""
    height, width = image.shape[:2]
    rows = slice(int(0.35 * height), int(0.65 * height))
    left = image[rows, int(0.2 * width):int(0.4 * width)]
    right = image[rows, int(0.6 * width):int(0.8 * width)]
    return np.array([left.reshape(-1, 3).mean(axis=0), right.reshape(-1, 3).mean(axis=0)])


def delta_e(image) -> float:
    """CIEDE2000 between the two paints as rendered (Lab white: the image's own grey card)."""
    colour = cie.import_colour()
    xyz = cie.linear_rec709_to_xyz(patch_colours(image))
    card = cie.linear_rec709_to_xyz(image[2:6, 2:6].reshape(-1, 3).mean(axis=0)) / BACKDROP_GREY
    lab = colour.XYZ_to_Lab(xyz / card[1], colour.XYZ_to_xy(card))
    return float(colour.delta_E(lab[0], lab[1], method="CIE 2000"))


def main(output: str) -> None:
    colour = cie.import_colour()
    rows = [render(light) for light in LIGHTS]
    for light, image in zip(LIGHTS, rows):
        print(f"{light}: ΔE2000 between the paints {delta_e(image):.2f}")
    exposure = 0.8 / max(patch_colours(image).max() for image in rows)
    gap = np.ones((4, rows[0].shape[1], 3))
    picture = np.concatenate([rows[0] * exposure, gap, rows[1] * exposure])
    encoded = np.clip(colour.cctf_encoding(np.clip(picture, 0.0, 1.0)), 0.0, 1.0)
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    import imageio.v2 as imageio

    imageio.imwrite(output, (encoded * 255.0 + 0.5).astype(np.uint8))
    print(f"wrote {output}")


if __name__ == "__main__":
    import warnings

    warnings.simplefilter("ignore")  # colour-science's notes on resampling its tables
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/images/metamerism.png")
