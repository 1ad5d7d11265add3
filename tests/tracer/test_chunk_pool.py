"""Worker threads: one per available core at most (``chunk_pool.worker_threads``), and the same image at any
thread count, oversubscribed or not."""

import numpy as np

from engine.tracer import chunk_pool
from engine.tracer.chunk_pool import available_cores, worker_threads
from engine.tracer.renderer import Renderer

from .tracer_scenes import plane_under_point_light, settings


def test_threads_are_capped_at_the_cores_this_process_may_use(monkeypatch):
    monkeypatch.setattr(chunk_pool.os, "sched_getaffinity", lambda pid: {0, 1, 2}, raising=False)
    assert available_cores() == 3
    assert [worker_threads(t) for t in (0, -1, 1, 2, 3, 16)] == [3, 3, 1, 2, 3, 3]


def test_oversubscribed_threads_render_the_image_of_one_thread():
    images = []
    for threads in (1, available_cores() * 8):
        with Renderer(plane_under_point_light(size=48), settings(samples=2, samples_per_pass=2, threads=threads)) as r:
            assert r._pool.workers == min(threads, available_cores())
            r.render_pass()
            images.append(r.image_rgb())
    assert np.array_equal(images[0], images[1])
