"""Grid-medium walks one ray at a time, for the tests of ``media.delta_tracking`` and ``media.ratio_tracking``
(``test_grid_tracking``, ``test_brick_majorants``)."""

from collections import namedtuple

from engine.tracer.jit import kernel
from engine.tracer.media.delta_tracking import track_grid_medium
from engine.tracer.media.ratio_tracking import ratio_track

#: The kernel settings a walk reads: the sampler.
Settings = namedtuple("Settings", "sampler")


@kernel
def ratio_estimates(media, spectra, wavelengths, o, d, distance, out, scratch):
    """``out[r]``: ratio tracking's transmittance estimate of medium 0 along ``o`` + s ``d`` (s up to ``distance``)
    per wavelength, for sample r."""
    for r in range(out.shape[0]):
        for k in range(out.shape[1]):
            out[r, k] = 1.0
        ratio_track(media, spectra, 0, wavelengths, o, d, distance, out[r], scratch, 977, r, 13)


@kernel
def delta_track(state, media, spectra, settings, t, collisions, sigma_t, sigma_s, f, p):
    """``collisions[i]``: where path ``i`` of ``state`` scatters in its grid medium before ``t`` (inf: it passes)."""
    for i in range(collisions.shape[0]):
        collisions[i] = track_grid_medium(state, i, t, media, spectra, settings, 0, sigma_t, sigma_s, f, p)
