"""Film ▸ Exposure (``RenderSettings.film_exposure``, Cycles' ``film_exposure``): a linear scale of the
light passes (Combined and what adds up to it, light groups), never of data or colour passes."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.pass_table import PassRequest
from engine.tracer.renderer import Renderer
from tracer.tracer_scenes import settings
from tracer.test_passes import _facing_wall

_PASSES = ("Depth", "Normal", "DiffDir", "DiffInd", "DiffCol")


def _render(exposure):
    with Renderer(_facing_wall(), settings(samples=4, film_exposure=exposure,
                                           passes=PassRequest(_PASSES, light_groups=()))) as r:
        while not r.finished:
            r.render_pass()
        return r.image_rgb().astype(np.float64), r.film.variance_of_mean(), r.pass_images()


def test_exposure_scales_light_passes_only():
    image, variance, passes = _render(1.0)
    image2, variance2, passes2 = _render(2.0)
    assert image.mean() > 0
    assert np.allclose(image2, 2.0 * image, rtol=1e-6)
    assert np.allclose(variance2, 4.0 * variance, rtol=1e-6)
    for name in ("DiffDir", "DiffInd"):
        assert np.allclose(passes2[name], 2.0 * passes[name], rtol=1e-6), name
    for name in ("Depth", "Normal", "DiffCol"):
        assert np.array_equal(passes2[name], passes[name]), name
    # DiffDir × DiffCol still adds up to the (exposed) image, as in Cycles' compositing.
    assert np.allclose(passes2["DiffDir"] * passes2["DiffCol"], image2, rtol=1e-4, atol=1e-6)


@pytest.mark.parametrize("bad", [-1.0, float("nan"), float("inf")])
def test_exposure_that_is_no_scale_is_refused(bad):
    with pytest.raises(PrismInputError, match="Film Exposure"):
        settings(film_exposure=bad).validate()
