"""Scenes without media render bit for bit as before media existed: the image hashes below were recorded
on ``main`` at 48b8d14 (before this code) by ``python -m tests.tracer.media.no_media_scene``; and such a
scene's tables say there are no media, so the kernels never enter the media code."""

import pytest

from engine.tracer.renderer import Renderer

from ..tracer_scenes import settings
from .no_media_scene import image_hash, no_media_scene

RECORDED_ON_MAIN = {
    "cie": "c17141cf3a816efe304b26cc995bf62eeb24f60e635126e6e5688a81ba4f736a",
    "gaussian_rgb": "bac103dd774ce310600518f95326365adf3206564b2eff5e8df3f0c95542c0e7",
}


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_scene_without_media_renders_bit_for_bit_as_on_main(mode):
    assert image_hash(mode) == RECORDED_ON_MAIN[mode]


def test_scene_without_media_takes_the_media_free_path():
    r = Renderer(no_media_scene(), settings())
    assert r.tables.kernel_settings.has_media is False
    assert (r.tables.material_table.arrays.medium == -1).all()
