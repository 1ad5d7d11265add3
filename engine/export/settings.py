"""``Scene.prism`` → ``tracer.settings.RenderSettings``."""

from __future__ import annotations

from ..tracer.errors import PrismInputError
from ..tracer.settings import RenderSettings

_MODES = {"CIE": "cie", "GAUSSIAN_RGB": "gaussian_rgb"}


def export_settings(
    scene,
    samples: int | None = None,
    seed: int | None = None,
    threads: int | None = None,
    preview: bool = False,
    border: tuple[int, int, int, int] | None = None,
) -> RenderSettings:
    """Render settings from the scene's Prism settings.

    ``samples``/``seed``/``threads`` override the scene's (batch renders);
    ``preview`` uses the preview sample count; ``border`` is the pixel rectangle
    (x0, y0, x1, y1), rows from the top, half-open.
    """
    prism = scene.prism
    if samples is None:
        samples = prism.preview_samples if preview else prism.samples
    settings = RenderSettings(
        samples=int(samples),
        samples_per_pass=int(prism.samples_per_pass),
        max_bounces=int(prism.max_bounces),
        seed=int(prism.seed if seed is None else seed),
        wavelength_mode=_MODES[prism.wavelength_mode],
        wavelengths_per_path=int(prism.wavelengths_per_path),
        channel_means_nm=tuple(float(v) for v in prism.channel_means_nm()),
        channel_sigmas_nm=tuple(float(v) for v in prism.channel_sigmas_nm()),
        threads=int(prism.threads if threads is None else threads),
        use_mis=bool(prism.use_mis),
        russian_roulette_depth=int(prism.russian_roulette_depth),
        border=border,
        pixel_filter=prism.pixel_filter.lower(),
        filter_width_px=float(prism.filter_width_px),
        film_transparent=bool(scene.render.film_transparent),
    )
    cycles = getattr(scene, "cycles", None)
    if cycles is not None:  # Film ▸ Transparent ▸ Transparent Glass lives in Cycles' settings
        settings.transparent_glass = bool(cycles.film_transparent_glass)
        settings.transparent_roughness = float(cycles.film_transparent_roughness)
    try:
        settings.validate()
    except PrismInputError as error:  # stored past the UI's limits (a script, an old file): say where
        raise PrismInputError(f"Scene '{scene.name}', Render Properties ▸ Prism: {error}") from None
    return settings
