"""The ceiling's ray recorder and replayer on the compiled core's Accel, and the stage split."""

import numpy as np
import pytest

from benchmarks import ceiling, scenes, stage_split
from benchmarks.prism_runs import settings_for
from engine.tracer.renderer import Renderer
from engine.tracer.stages import trace


@pytest.fixture(scope="module")
def glass_scene():
    return scenes.build("cornell_glass", (8, 8))


def test_recorder_sees_every_ray_the_renderer_counts(glass_scene):
    with Renderer(glass_scene, settings_for({}, samples=8, seed=1, threads=2)) as renderer:
        renderer.render_pass()
        before = renderer.stats["rays_cast"]
        recorder = ceiling.record_pass(renderer)
        counted = renderer.stats["rays_cast"] - before
        assert "intersect" not in vars(renderer.tables.accel)  # the class's methods are back
    assert recorder.ray_count == counted > 0
    assert recorder.count(ceiling.CLOSEST) > 0 and recorder.count(ceiling.OCCLUDED) > 0
    for kind, origin, direction, tmax in recorder.batches:
        assert origin.dtype == direction.dtype == np.float32 and origin.shape == direction.shape
        assert (tmax is None) == (kind == ceiling.CLOSEST)


def test_replay_finds_the_renderers_hits(glass_scene):
    """Replayed on the renderer's camera-relative triangles, every closest-hit query finds the renderer's hits."""
    with Renderer(glass_scene, settings_for({}, samples=4, seed=2, threads=1)) as renderer:
        hits = []
        query = renderer.tables.accel.intersect

        def keep(rays, count):
            out = query(rays, count)
            hits.append(out[0].copy())
            return out

        renderer.tables.accel.intersect = keep
        recorder = ceiling.RayRecorder(renderer.tables.accel)
        recorder.active = True
        renderer.render_pass()
        recorder.uninstall()
        replayer = ceiling.Replayer(renderer.tables.geometry, recorder.batches, threads=1)
        closest = [b for b in recorder.batches if b[0] == ceiling.CLOSEST]
        again = [replayer.scene.run(o, d, output=1)["primID"] for _, o, d, _ in closest]
        replayer.close()
    assert len(again) == len(hits) > 1
    for replayed, recorded in zip(again, hits):
        np.testing.assert_array_equal(replayed, recorded)
    assert (hits[0] >= 0).mean() > 0.5


def test_stage_split_accounts_for_the_chunks_and_restores_the_kernels(glass_scene):
    originals = {name: getattr(trace, name) for _, names in stage_split.KERNEL_STAGES for name in names}
    originals[stage_split.CHUNK] = getattr(trace, stage_split.CHUNK)
    split = stage_split.stage_split(glass_scene, {}, threads=1, passes=1)
    assert {name: getattr(trace, name) for name in originals} == originals
    rows = {r["stage"]: r for r in split["rows"]}
    assert rows["shade (BSDF, light sampling, roulette)"]["calls"] > 0
    assert rows["Embree closest hits"]["calls"] > 0
    in_chunks = [r for r in split["rows"] if np.isfinite(r["share"])]
    assert sum(r["share"] for r in in_chunks) == pytest.approx(1.0, abs=1e-6)
    assert split["paths"] == 8 * 8 * 16
