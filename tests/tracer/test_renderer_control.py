"""The Renderer's public control API: start mid-sequence, cancel, close."""

import threading

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.renderer import Renderer

from .tracer_scenes import plane_under_point_light, settings


def _film_sum(renderer):
    return renderer.film.mean() * renderer.film.counts[..., None]


def test_chunks_started_mid_sequence_merge_bit_identically():
    scene = plane_under_point_light(size=16)
    with Renderer(scene, settings(samples=4, samples_per_pass=2, seed=5)) as whole:
        whole.render_pass()
        whole.render_pass()
        full = _film_sum(whole)
    with Renderer(scene, settings(samples=2, samples_per_pass=2, seed=5)) as a, \
            Renderer(scene, settings(samples=2, samples_per_pass=2, seed=5)) as b:
        a.render_pass()
        b.start_at_sample(2)
        b.render_pass()
        assert a.samples_done == 2 and b.samples_done == 4
        assert np.array_equal(_film_sum(a) + _film_sum(b), full)


def test_start_offset_must_be_a_multiple_of_the_pass_and_come_first():
    scene = plane_under_point_light(size=8)
    with Renderer(scene, settings(samples=4, samples_per_pass=2)) as r:
        with pytest.raises(PrismInputError):
            r.start_at_sample(3)
        r.render_pass()
        with pytest.raises(RuntimeError):
            r.start_at_sample(2)


def test_cancel_from_progress_stops_the_pass_and_keeps_finished_chunks():
    scene = plane_under_point_light(size=48)
    s = settings(samples=64, samples_per_pass=64, threads=1)  # 48 x 48 x 64 paths: several chunks
    calls = []
    with Renderer(scene, s) as r:
        def progress(fraction):
            calls.append(fraction)
            r.cancel()

        r.progress = progress
        r.render_pass()
        assert len(calls) == 1 and calls[0] < 1.0
        assert r.cancelled and r.samples_done == 0
        assert r.film.counts.sum() > 0  # the first chunk's samples are kept
        r.render_pass()  # a cancelled renderer does no more work
        assert len(calls) == 1


def test_cancel_from_another_thread_and_close_twice():
    scene = plane_under_point_light(size=48)
    r = Renderer(scene, settings(samples=64, samples_per_pass=64))
    timer = threading.Timer(0.01, r.cancel)
    timer.start()
    r.render_pass()
    timer.join()
    assert r.cancelled or r.samples_done == 64  # cancelled, unless the pass was already over
    r.close()
    r.close()
