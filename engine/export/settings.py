"""``Scene.prism`` → ``tracer.settings.RenderSettings``."""

from ..tracer.settings import RenderSettings

_MODES = {"CIE": "cie", "GAUSSIAN_RGB": "gaussian_rgb"}


def export_settings(scene, samples: int | None = None, seed: int | None = None) -> RenderSettings:
    """Render settings from the scene's Prism settings; ``samples``/``seed`` override them."""
    defaults = RenderSettings()
    prism = getattr(scene, "prism", None)

    def value(name, default):
        return getattr(prism, name, default) if prism is not None else default

    settings = RenderSettings(
        samples=int(samples if samples is not None else value("samples", 64)),
        samples_per_pass=int(value("samples_per_pass", defaults.samples_per_pass)),
        max_bounces=int(value("max_bounces", defaults.max_bounces)),
        seed=int(seed if seed is not None else value("seed", defaults.seed)),
        wavelength_mode=_MODES.get(value("wavelength_mode", "CIE"), "cie"),
        wavelengths_per_path=int(value("wavelengths_per_path", defaults.wavelengths_per_path)),
        channel_means_nm=(
            float(value("mean_r_nm", 600.0)),
            float(value("mean_g_nm", 550.0)),
            float(value("mean_b_nm", 450.0)),
        ),
        channel_sigmas_nm=(
            float(value("sigma_r_nm", 25.0)),
            float(value("sigma_g_nm", 25.0)),
            float(value("sigma_b_nm", 15.0)),
        ),
        threads=int(value("threads", defaults.threads)),
        use_mis=bool(value("use_mis", defaults.use_mis)),
        russian_roulette_depth=int(value("russian_roulette_depth", defaults.russian_roulette_depth)),
    )
    settings.validate()
    return settings
