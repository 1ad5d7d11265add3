"""Adaptive sampling and the time limit."""

import time

import numpy as np

from engine.tracer.adaptive import automatic_min_samples, pixel_error, still_sampling
from engine.tracer.renderer import Renderer

from .tracer_scenes import plane_under_point_light, settings


def test_error_is_relative_to_brightness_and_active_regions_grow():
    mean = np.full((5, 5, 3), 0.25)
    variance = np.zeros((5, 5, 3))
    variance[2, 2] = (0.01 / 3 * np.sqrt(0.75)) ** 2
    error = pixel_error(mean, variance)
    assert error[2, 2] == np.float64(error[2, 2]) and abs(error[2, 2] - 0.01) < 1e-6 and error[0, 0] == 0
    active = still_sampling(mean, variance, 0.005)
    assert active.sum() == 5 and active[1, 2] and active[2, 1] and not active[1, 1]
    assert automatic_min_samples(1000, 0.01) == 16 and automatic_min_samples(8, 0.01) == 8


def test_converged_pixels_stop_and_noisy_ones_go_on():
    # Under a point light the bright centre of the floor is noisier (relative to the square root of its
    # brightness) than the dim edges, so the edges converge first.
    scene = plane_under_point_light(size=16)
    s = settings(samples=64, samples_per_pass=4, adaptive_threshold=0.03, adaptive_min_samples=8)
    with Renderer(scene, s) as r:
        while not r.finished:
            r.render_pass()
        counts = r.film.counts
        image = r.image_rgb()
    assert counts.min() >= 8 and counts.mean() < 0.8 * 64
    assert counts[[0, 0, -1, -1], [0, -1, 0, -1]].max() < counts[6:10, 6:10].min()
    with Renderer(scene, settings(samples=64, samples_per_pass=4)) as uniform:
        while not uniform.finished:
            uniform.render_pass()
        reference = uniform.image_rgb()
    assert abs(image.mean() / reference.mean() - 1) < 0.02
    assert np.abs(image - reference).max() < 0.1 * reference.max()


def test_time_limit_stops_sampling():
    scene = plane_under_point_light(size=16)
    with Renderer(scene, settings(samples=100000, samples_per_pass=4, time_limit_s=1.0)) as r:
        started = time.perf_counter()
        while not r.finished:
            r.render_pass()
        assert r.time_up and time.perf_counter() - started < 5.0
        assert 0 < r.samples_done < 100000 and np.all(r.film.counts == r.samples_done)
