"""Scenes without media render bit for bit as if media did not exist: the kernels' media code, switched on
for a scene that has no medium, changes no bit of its image; and such a scene's tables leave it switched off,
so the kernels never enter it.

History: the image hashes of this scene recorded on ``main`` before media existed (48b8d14) still held when
media were merged (25abc54). Motion blur's merge (aba9130) restructured ``geometry.surface_at`` and the
camera ray and changed the last float32 place of about 10 % of the values (means equal to 17 digits), so
a recorded hash stopped being a test of media; the comparison below is independent of such changes.
"""

import pytest

from engine.tracer.renderer import Renderer

from ..tracer_scenes import settings
from .no_media_scene import image_hash, no_media_scene


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_the_media_code_changes_no_bit_of_a_scene_without_media(mode):
    assert image_hash(mode, media_code=True) == image_hash(mode)


def test_scene_without_media_takes_the_media_free_path():
    r = Renderer(no_media_scene(), settings())
    assert r.tables.kernel_settings.has_media is False
    assert (r.tables.material_table.arrays.medium == -1).all()
