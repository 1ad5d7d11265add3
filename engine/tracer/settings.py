"""Render settings the tracer needs: plain data, filled from ``Scene.prism`` in Blender."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import PrismInputError

WAVELENGTH_MODES = ("cie", "gaussian_rgb")


@dataclass
class RenderSettings:
    """How to render.

    ``samples``: samples per pixel in total; ``samples_per_pass``: added per
    progressive pass. ``wavelength_mode``: ``"cie"`` (hero wavelengths
    importance-sampled over 360-830 nm and integrated against the CIE 1931
    colour-matching functions) or ``"gaussian_rgb"`` (one wavelength per R, G, B
    channel, drawn from that channel's Gaussian, means/sigmas in nm).
    ``threads``: 0 uses every core. ``border``: (x0, y0, x1, y1) pixel rectangle,
    rows counted from the top, half-open; None renders the whole frame.
    """

    samples: int = 16
    samples_per_pass: int = 1
    max_bounces: int = 8
    seed: int = 0
    wavelength_mode: str = "cie"
    wavelengths_per_path: int = 4
    channel_means_nm: tuple[float, float, float] = (600.0, 550.0, 450.0)
    channel_sigmas_nm: tuple[float, float, float] = (25.0, 25.0, 15.0)
    threads: int = 0
    use_mis: bool = True
    russian_roulette_depth: int = 3
    use_pupil_bounds: bool = True
    border: tuple[int, int, int, int] | None = None
    # Pixel filter (tracer): "box" (uniform over the pixel) or "gaussian" (standard
    # deviation filter_width_px / 3, truncated at filter_width_px from the centre).
    pixel_filter: str = "box"
    filter_width_px: float = 1.5
    # Where every path's uniform numbers come from: "sobol" (Owen-scrambled, the default) or
    # "independent" (hashed random numbers, the reference the benchmark measures Sobol against).
    sampler: str = "sobol"
    # Film ▸ Transparent (Cycles' names): the background the camera sees becomes alpha 0; with
    # transparent_glass, so does what it sees through glass no rougher than transparent_roughness.
    film_transparent: bool = False
    transparent_glass: bool = False
    transparent_roughness: float = 0.1

    def validate(self) -> None:
        """Raise ``PrismInputError`` for settings no render can use."""
        if self.wavelength_mode not in WAVELENGTH_MODES:
            raise PrismInputError(
                f"Unknown wavelength mode '{self.wavelength_mode}': use one of {', '.join(WAVELENGTH_MODES)}."
            )
        if self.samples < 1:
            raise PrismInputError(f"Samples must be at least 1 (got {self.samples}).")
        if self.samples_per_pass < 1:
            raise PrismInputError(f"Samples per pass must be at least 1 (got {self.samples_per_pass}).")
        if self.max_bounces < 0:
            raise PrismInputError(f"Max bounces cannot be negative (got {self.max_bounces}).")
        if not 1 <= self.wavelengths_per_path <= 16:
            raise PrismInputError(
                f"Wavelengths per path must be between 1 and 16 (got {self.wavelengths_per_path})."
            )
        for channel, sigma in zip("RGB", self.channel_sigmas_nm):
            if not sigma > 0:
                raise PrismInputError(f"The {channel} channel's sigma must be positive (got {sigma} nm).")
