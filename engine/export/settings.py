"""``Scene.prism`` → ``tracer.settings.RenderSettings``."""

from __future__ import annotations

from ..tracer.errors import PrismInputError
from ..tracer.pass_table import PassRequest
from ..tracer.settings import RenderSettings
from .light_path_tricks import light_path_tricks

_MODES = {"CIE": "cie", "GAUSSIAN_RGB": "gaussian_rgb"}
#: Samples of a material or light preview (``preview=True``): Blender renders them in its own preview
#: scene, whose Prism settings are the defaults, so the count is fixed here; enough for a dispersive
#: glass to show its fringes on a thumbnail.
PREVIEW_SAMPLES = 16


def export_settings(
    scene,
    samples: int | None = None,
    seed: int | None = None,
    threads: int | None = None,
    preview: bool = False,
    border: tuple[int, int, int, int] | None = None,
    passes: PassRequest | None = None,
    spectral: bool = False,
) -> RenderSettings:
    """Render settings from the scene's Prism settings.

    ``samples``/``seed``/``threads`` override the scene's (batch renders);
    ``preview`` (a material or light preview) renders ``PREVIEW_SAMPLES`` with the
    viewport's bounces; ``border`` is the pixel rectangle (x0, y0, x1, y1), rows
    from the top, half-open; ``passes`` what besides Combined to render
    (``engine.render.result_passes.pass_request``); ``spectral`` keeps band radiance for a multispectral
    EXR (bands of the scene's Spectral Output width).
    """
    prism = scene.prism
    if spectral:  # checked here: a width of 0 would mean "no spectral film" and the EXR could not be written
        from ..tracer.spectral_film import band_edges_nm

        try:
            band_edges_nm(float(prism.spectral_band_nm))
        except PrismInputError as error:
            raise PrismInputError(f"Scene '{scene.name}': {error}") from None
    if samples is None:
        samples = PREVIEW_SAMPLES if preview else prism.samples
    settings = RenderSettings(
        samples=int(samples),
        samples_per_pass=int(prism.samples_per_pass),
        max_bounces=int(prism.preview_max_bounces if preview else prism.max_bounces),
        transparent_max_bounces=int(prism.transparent_max_bounces),
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
        light_tracing=prism.light_tracing.lower(),
        passes=passes if passes is not None else PassRequest(),
        adaptive_threshold=float(prism.adaptive_threshold) if prism.use_adaptive_sampling else 0.0,
        adaptive_min_samples=int(prism.adaptive_min_samples),
        time_limit_s=float(prism.time_limit),
        spectral_band_nm=float(prism.spectral_band_nm) if spectral else 0.0,
    )
    cycles = getattr(scene, "cycles", None)
    if cycles is not None:  # Film ▸ Transparent ▸ Transparent Glass lives in Cycles' settings
        settings.transparent_glass = bool(cycles.film_transparent_glass)
        settings.transparent_roughness = float(cycles.film_transparent_roughness)
        # Film ▸ Exposure: Prism has no exposure of its own, so Cycles' (the Film panel a converted scene
        # carries) applies, as the same linear scale of the light passes.
        settings.film_exposure = float(getattr(cycles, "film_exposure", 1.0))
    settings.light_path_tricks = light_path_tricks(scene)
    try:
        settings.validate()
    except PrismInputError as error:  # stored past the UI's limits (a script, an old file): say where
        raise PrismInputError(f"Scene '{scene.name}', Render Properties ▸ Prism: {error}") from None
    return settings
