"""Render settings the tracer needs: plain data, filled from ``Scene.prism`` in Blender."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .errors import PrismInputError
from .pass_table import PassRequest
from .path_tricks import LightPathTricks

WAVELENGTH_MODES = ("cie", "gaussian_rgb")
LIGHT_TRACING_MODES = ("auto", "off", "on")
PIXEL_FILTERS = ("box", "gaussian")


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
    # Cut-outs and films a path may go straight through (Cycles' Transparent Max Bounces), apart from max_bounces.
    transparent_max_bounces: int = 8
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
    # Caustics from light tracing (paths from the lights through specular objects, seen by the camera):
    # "auto" (where the scene analysis finds specular objects a light can shine through), "off", "on".
    light_tracing: str = "auto"
    # Passes besides Combined (``pass_table.PassRequest``).
    passes: PassRequest = field(default_factory=PassRequest)
    # Adaptive sampling (Cycles' Noise Threshold and Min Samples): a pixel stops once its relative
    # error (``adaptive.pixel_error``) is below the threshold; 0 = off. Min samples 0 = automatic.
    adaptive_threshold: float = 0.0
    adaptive_min_samples: int = 0
    # Stop sampling after this many seconds of rendering (scene preparation excluded); 0 = no limit.
    time_limit_s: float = 0.0
    # Multispectral output (``spectral_film``): band width in nm, 0 = off (no spectral buffer at all).
    spectral_band_nm: float = 0.0
    # Film ▸ Transparent (Cycles' names): the background the camera sees becomes alpha 0; with
    # transparent_glass, so does what it sees through glass no rougher than transparent_roughness.
    film_transparent: bool = False
    transparent_glass: bool = False
    transparent_roughness: float = 0.1
    # Film ▸ Exposure (Cycles' ``film_exposure``): a linear scale of every light pass (Combined, Emit,
    # Diffuse Direct, light groups, ...), not of data passes (Depth, Normal, colour passes). 1 = physical.
    film_exposure: float = 1.0
    # Cycles' Light Paths tricks (``path_tricks.LightPathTricks``): clamps, Filter Glossy, caustics toggles.
    # The default is none of them: an unbiased image.
    light_path_tricks: LightPathTricks = field(default_factory=LightPathTricks)

    def validate(self) -> None:
        """Raise ``PrismInputError`` for settings no render can use."""
        if not (self.film_exposure >= 0.0 and self.film_exposure < float("inf")):
            raise PrismInputError(f"Film Exposure {self.film_exposure} is not a finite scale ≥ 0: set Film ▸ "
                                  "Exposure between 0 and 10 (1 leaves the image as rendered).")
        self.light_path_tricks.validate()
        if self.wavelength_mode not in WAVELENGTH_MODES:
            raise PrismInputError(
                f"Unknown wavelength mode '{self.wavelength_mode}': use one of {', '.join(WAVELENGTH_MODES)}."
            )
        if self.light_tracing not in LIGHT_TRACING_MODES:
            raise PrismInputError(
                f"Unknown light tracing mode '{self.light_tracing}': use one of {', '.join(LIGHT_TRACING_MODES)}."
            )
        if self.pixel_filter not in PIXEL_FILTERS:
            raise PrismInputError(f"Pixel filter '{self.pixel_filter}' is unknown: use one of {', '.join(PIXEL_FILTERS)}.")
        if not (math.isfinite(self.filter_width_px) and self.filter_width_px > 0):
            raise PrismInputError(
                f"Filter Width must be above 0 pixels (got {self.filter_width_px:g}): set it to e.g. 1.5 (the pixel "
                "filter's reach in pixels; Blender's smallest is 0.01)."
            )
        if self.samples < 1:
            raise PrismInputError(f"Samples must be at least 1 (got {self.samples}).")
        if self.samples_per_pass < 1:
            raise PrismInputError(f"Samples per pass must be at least 1 (got {self.samples_per_pass}).")
        if self.max_bounces < 0:
            raise PrismInputError(f"Max bounces cannot be negative (got {self.max_bounces}).")
        if self.transparent_max_bounces < 0:
            raise PrismInputError(f"Transparent max bounces cannot be negative (got {self.transparent_max_bounces}).")
        if not 1 <= self.wavelengths_per_path <= 16:
            raise PrismInputError(
                f"Wavelengths per path must be between 1 and 16 (got {self.wavelengths_per_path})."
            )
        if self.spectral_band_nm:
            from .spectral_film import band_edges_nm

            band_edges_nm(self.spectral_band_nm)
            if self.wavelength_mode != "cie":
                raise PrismInputError(
                    "Spectral output needs CIE hero wavelengths: Gaussian RGB mode samples only around its three "
                    "channels, so most bands would stay empty. Set Render ▸ Prism ▸ Wavelengths to CIE, or turn "
                    "Spectral Output off."
                )
        for channel, sigma in zip("RGB", self.channel_sigmas_nm):
            if not sigma > 0:
                raise PrismInputError(f"The {channel} channel's sigma must be positive (got {sigma} nm).")
        if not 0.0 <= self.adaptive_threshold < 1.0:
            raise PrismInputError(
                f"The noise threshold must be between 0 (off) and 1 (got {self.adaptive_threshold}): 0.01 is typical."
            )
        if self.adaptive_min_samples < 0:
            raise PrismInputError(f"Min samples cannot be negative (got {self.adaptive_min_samples}; 0 = automatic).")
        if not self.time_limit_s >= 0.0:
            raise PrismInputError(f"The time limit cannot be negative (got {self.time_limit_s} s; 0 = no limit).")
        self.passes.validate()
