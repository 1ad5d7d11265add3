"""End to end: a distant small lamp rendered through the uncorrected singlet focuses blue
and red at different film distances (longitudinal chromatic aberration)."""

import math

import numpy as np
import pytest

from engine.tracer.lens.catalogue import LENS_DIRECTORY
from engine.tracer.lens.focus import best_focus
from engine.tracer.lens.lens_file import load_lens
from engine.tracer.lens.paraxial import image_distance_mm
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, Scene, SpectrumSpec
from engine.tracer.settings import RenderSettings

SINGLET = str(LENS_DIRECTORY / "singlet_bk7_100mm.lens")
SIZE = 24
FILM_MM = 0.9  # 37.5 um pixels: the red blur (~0.2 mm across) spans several pixels


def _render(sensor_distance_mm):
    half = 0.01  # a 2 cm lamp 50 m away images to 0.04 mm
    vertices = np.array([[-half, -half, -50.0], [half, -half, -50.0], [half, half, -50.0], [-half, half, -50.0]],
                        dtype=np.float32)
    lamp = Material("lamp", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec("rgb", (1.0, 1.0, 1.0)),
                    emission_strength=2000.0)
    camera = Camera("cam", np.eye(4), (SIZE, SIZE), film_width_mm=FILM_MM, film_height_mm=FILM_MM, model="real_lens",
                    lens_file=SINGLET, fstop=8.0, sensor_distance_mm=sensor_distance_mm)
    scene = Scene(vertices, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32), np.zeros(2, dtype=np.int32), [lamp],
                  camera)
    settings = RenderSettings(samples=48, samples_per_pass=48, seed=3, threads=2, wavelength_mode="gaussian_rgb")
    renderer = Renderer(scene, settings)
    renderer.render_pass()
    return renderer.image_rgb().astype(np.float64)


def _spread_px(channel):
    """RMS radius (pixels) of a channel's light about its centroid."""
    y, x = np.mgrid[0:SIZE, 0:SIZE] + 0.5
    w = np.clip(channel, 0.0, None)
    cx, cy = (w * x).sum() / w.sum(), (w * y).sum() / w.sum()
    return math.sqrt((w * ((x - cx) ** 2 + (y - cy) ** 2)).sum() / w.sum())


def test_blue_and_red_focus_at_different_film_distances():
    lens = load_lens(SINGLET)
    blue_focus = best_focus(lens, -math.inf, 450.0).sensor_distance_mm  # the B channel's mean wavelength
    red_focus = best_focus(lens, -math.inf, 600.0).sensor_distance_mm  # the R channel's
    paraxial = image_distance_mm(lens, -math.inf, 600.0) - image_distance_mm(lens, -math.inf, 450.0)
    assert red_focus - blue_focus == pytest.approx(paraxial, rel=0.03)  # 1.70 mm
    at_blue = _render(blue_focus)
    at_red = _render(red_focus)
    assert np.isfinite(at_blue).all() and at_blue.max() > 0
    red_at_blue, blue_at_blue = _spread_px(at_blue[..., 0]), _spread_px(at_blue[..., 2])
    red_at_red, blue_at_red = _spread_px(at_red[..., 0]), _spread_px(at_red[..., 2])
    print(f"spread px: at blue focus B {blue_at_blue:.2f} R {red_at_blue:.2f}; at red focus B {blue_at_red:.2f} R {red_at_red:.2f}")
    # Each channel is sharp at its own focus and blurred at the other's.
    assert blue_at_blue < 0.6 * red_at_blue
    assert red_at_red < 0.6 * blue_at_red
    assert red_at_red < 0.6 * red_at_blue and blue_at_blue < 0.6 * blue_at_red
