"""White furnace: a sphere of albedo-1 medium (Volume Scatter, white: σ_a = 0) inside a null surface
scatters light without absorbing any, so it vanishes against a uniform surround, for isotropic, forward
and backward phase functions. Under a uniform white world (a constant world is not light-sampled, so
this checks distance sampling, phase sampling and the boundary crossings: every weight must stay exactly
1); inside a glowing closed emitter (a mesh light: this checks light sampling from medium vertices, the
shadow rays' transmittance through the medium and across its null boundary, and MIS with the phase
function)."""

import numpy as np
import pytest

from engine.tracer.media.spec import MediumSpec
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, World
from engine.tracer.spectra.rgb_to_spectrum import white_rgb

from ..tracer_scenes import look_at, make_scene, settings, uv_sphere


def _fog_ball(g, density):
    cam = Camera("cam", look_at((0, -4.0, 0), (0, 0, 0)), (12, 12), film_width_mm=20.0, film_height_mm=20.0)
    ball = uv_sphere((0, 0, 0), 1.0, rings=16, segments=32)
    medium = MediumSpec("fog", scatter=[(density, (1.0, 1.0, 1.0))], anisotropy=g)
    return make_scene([(*ball, 0)], [Material("fog", kind="null", medium=medium)], cam,
                      world=World(color=(1.0, 1.0, 1.0), strength=1.0))


@pytest.mark.parametrize("g, use_mis", [(0.0, True), (0.8, True), (-0.5, False)])
def test_scattering_sphere_vanishes_in_a_white_furnace(g, use_mis):
    s = settings(samples=32, samples_per_pass=32, max_bounces=128, use_mis=use_mis)
    r = Renderer(_fog_ball(g, density=2.0), s)
    r.render_pass()
    img = r.image_rgb().astype(np.float64)
    white = np.asarray(white_rgb())
    luminance = np.array([0.2126729, 0.7151522, 0.0721750])
    ratio = img.mean((0, 1)) @ luminance / (white @ luminance)
    stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) @ luminance ** 2 / img[..., 0].size)
    print(f"MEASURED furnace g={g} mis={use_mis}: luminance / world = {ratio:.4f} (stderr {stderr:.4f})")
    assert ratio == pytest.approx(1.0, abs=0.01)
    assert r.stats["nan_samples"] == 0


def _glowing_enclosure(ball_medium, g):
    """A fog ball of radius 1 inside a closed, inward-facing, black emitter of strength 1 (radius 3), seen
    from inside: the emitter is a mesh light, so light sampling from the medium runs, its shadow rays
    crossing the null boundary with the medium's transmittance, MIS-weighted against phase sampling."""
    from engine.tracer.scene import SpectrumSpec

    cam = Camera("cam", look_at((0, -2.5, 0), (0, 0, 0)), (12, 12), film_width_mm=30.0, film_height_mm=30.0)
    shell = uv_sphere((0, 0, 0), 3.0, rings=12, segments=24, inward=True)
    glow = Material("glow", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    parts, materials = [(*shell, 0)], [glow]
    if ball_medium is not None:
        parts.append((*uv_sphere((0, 0, 0), 1.0, rings=16, segments=32), 1))
        materials.append(Material("fog", kind="null", medium=ball_medium))
    return make_scene(parts, materials, cam)


@pytest.mark.parametrize("g", [0.0, 0.6])
def test_scattering_sphere_vanishes_inside_a_glowing_enclosure_with_light_sampling(g):
    luminance = np.array([0.2126729, 0.7151522, 0.0721750])
    means = []
    for medium in (None, MediumSpec("fog", scatter=[(1.5, (1.0, 1.0, 1.0))], anisotropy=g)):
        r = Renderer(_glowing_enclosure(medium, g), settings(samples=128, samples_per_pass=128, max_bounces=128))
        r.render_pass()
        img = r.image_rgb().astype(np.float64)
        means.append(img.mean((0, 1)) @ luminance)
        stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) @ luminance ** 2 / img[..., 0].size)
        assert r.stats["nan_samples"] == 0
    ratio = means[1] / means[0]
    print(f"MEASURED glowing enclosure g={g}: luminance with fog ball / without = {ratio:.4f} "
          f"(stderr {stderr / means[0]:.4f})")
    assert ratio == pytest.approx(1.0, abs=0.01)
