"""The Light Path node's bookkeeping (``materials.light_path``) against Cycles' ``path_state_next``: what each
kind of scattering does to the ray kind and the bounce counts, and what each caller writes for the node."""

from collections import namedtuple

import numpy as np
import pytest

from engine.tracer.bsdf.closure import SAMPLED_DELTA, SAMPLED_DIFFUSE, SAMPLED_TRANSMISSION
from engine.tracer.materials import light_path as lp

State = namedtuple("State", "light_path ray_travelled hit_t")


def _outputs(regs):
    return dict(zip(lp.OUTPUTS, regs[-lp.FIELDS:].tolist()))


@pytest.fixture
def state():
    s = State(np.zeros((1, lp.RECORD), np.int32), np.zeros(1), np.zeros(1))
    lp.start_camera_ray(s, 0)
    return s


def _seen(state, length=1.0):
    regs = np.full(4 + lp.FIELDS, -1.0)
    lp.path_ray(regs, state, 0, length)
    assert np.all(regs[:4] == -1.0)  # the program's own registers are left alone
    return _outputs(regs)


def test_a_camera_ray_is_only_a_camera_ray(state):
    seen = _seen(state, 2.5)
    assert seen["Is Camera Ray"] == 1.0 and seen["Ray Length"] == 2.5
    assert sum(seen[name] for name in lp.OUTPUTS if name not in ("Is Camera Ray", "Ray Length")) == 0.0


def test_each_scattering_sets_the_ray_kind_and_counts_as_cycles(state):
    lp.after_scattering(state, 0, SAMPLED_DIFFUSE)  # a diffuse reflection
    seen = _seen(state)
    assert (seen["Is Diffuse Ray"], seen["Is Reflection Ray"], seen["Ray Depth"], seen["Diffuse Depth"]) == (1, 1, 1, 1)
    assert seen["Is Camera Ray"] == seen["Is Glossy Ray"] == seen["Is Transmission Ray"] == seen["Is Singular Ray"] == 0
    lp.after_scattering(state, 0, SAMPLED_DIFFUSE | SAMPLED_TRANSMISSION)  # translucent: diffuse and transmit
    seen = _seen(state)
    assert (seen["Is Diffuse Ray"], seen["Is Transmission Ray"], seen["Is Reflection Ray"]) == (1, 1, 0)
    assert (seen["Ray Depth"], seen["Diffuse Depth"], seen["Transmission Depth"]) == (2, 1, 1)
    lp.after_scattering(state, 0, SAMPLED_DELTA)  # a mirror: glossy, singular, reflection
    seen = _seen(state)
    assert (seen["Is Glossy Ray"], seen["Is Singular Ray"], seen["Is Reflection Ray"], seen["Glossy Depth"]) == (1, 1, 1, 1)
    lp.after_scattering(state, 0, SAMPLED_TRANSMISSION)  # rough refraction: glossy transmission, not singular
    seen = _seen(state)
    assert (seen["Is Glossy Ray"], seen["Is Singular Ray"], seen["Is Transmission Ray"]) == (1, 0, 1)
    assert (seen["Ray Depth"], seen["Diffuse Depth"], seen["Glossy Depth"], seen["Transmission Depth"]) == (4, 1, 1, 2)
    lp.after_volume_scatter(state, 0)
    seen = _seen(state)
    assert seen["Is Volume Scatter Ray"] == 1.0 and seen["Ray Depth"] == 5 and seen["Is Glossy Ray"] == 0


def test_a_transparent_crossing_keeps_the_kind_and_the_length_goes_on(state):
    state.hit_t[0] = 3.0
    lp.after_transparent(state, 0, True)
    seen = _seen(state, 1.5)
    assert seen["Is Camera Ray"] == 1.0 and seen["Transparent Depth"] == 1 and seen["Ray Depth"] == 0
    assert seen["Ray Length"] == 4.5
    lp.after_transparent(state, 0, False)  # a volume's boundary: no bounce of any kind, the length goes on
    seen = _seen(state, 1.5)
    assert seen["Transparent Depth"] == 1 and seen["Ray Length"] == 7.5
    lp.after_scattering(state, 0, SAMPLED_DIFFUSE)
    assert _seen(state, 1.5)["Ray Length"] == 1.5  # a new ray after a scattering


def test_shadow_rays_and_light_sampling_see_one_bounce_further(state):
    lp.after_scattering(state, 0, SAMPLED_DIFFUSE)
    regs = np.zeros(lp.FIELDS)
    lp.shadow_ray(regs, state, 0, 2, 0.7)
    seen = _outputs(regs)
    assert seen["Is Shadow Ray"] == 1.0 and seen["Is Diffuse Ray"] == 0.0 and seen["Is Camera Ray"] == 0.0
    assert (seen["Ray Depth"], seen["Transparent Depth"], seen["Ray Length"]) == (2, 2, 0.7)
    lp.emission_sample(regs, state, 0)
    lp.sampled_distance(regs, 3.25)
    seen = _outputs(regs)
    assert sum(seen[name] for name in lp.OUTPUTS[:8]) == 0.0  # no ray kind (Cycles' PATH_RAY_EMISSION)
    assert (seen["Ray Depth"], seen["Ray Length"]) == (2, 3.25)
