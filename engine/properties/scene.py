"""``Scene.prism``: render settings stored in the .blend (the session turns them into ``RenderSettings``)."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from ..tracer.spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM
from ._common import WAVELENGTH_SUBTYPE, register_group, unregister_group
from .file_path import BLEND_RELATIVE_PATH_OPTIONS
from .farm import PrismFarmSettings
from .lens_overlay import PrismLensOverlaySettings

WAVELENGTH_MODE_ITEMS = [
    (
        "CIE",
        "CIE hero wavelengths",
        "Sample several wavelengths per path over 360-830 nm and integrate them against the "
        "CIE 1931 colour-matching functions (physically correct colour)",
        0,
    ),
    (
        "GAUSSIAN_RGB",
        "Gaussian RGB",
        "Trace one wavelength per R, G and B channel, drawn from that channel's Gaussian "
        "(the original spectral ray tracer's model)",
        1,
    ),
]


def _update_render_passes(self, context):
    scene = self.id_data
    for view_layer in scene.view_layers:
        view_layer.update_render_passes()


def _mean(channel: str, default: float):
    return FloatProperty(
        name=f"{channel} Mean",
        description=f"Centre wavelength in nm of the {channel} channel's Gaussian (Gaussian RGB mode)",
        default=default,
        min=VISIBLE_MIN_NM,
        max=VISIBLE_MAX_NM,
        subtype=WAVELENGTH_SUBTYPE,
    )


def _sigma(channel: str, default: float):
    return FloatProperty(
        name=f"{channel} Sigma",
        description=f"Standard deviation in nm of the {channel} channel's Gaussian (Gaussian RGB mode)",
        default=default,
        min=0.5,
        max=200.0,
        subtype=WAVELENGTH_SUBTYPE,
    )


class PrismSceneSettings(bpy.types.PropertyGroup):
    """Prism render settings of a scene."""

    samples: IntProperty(
        name="Samples",
        description="Samples per pixel of a final render",
        default=64,
        min=1,
        soft_max=4096,
    )
    samples_per_pass: IntProperty(
        name="Samples per Pass",
        description="Samples added to every pixel before the image is shown again (higher is faster overall, "
        "lower refreshes more often)",
        default=1,
        min=1,
        soft_max=64,
    )
    preview_samples: IntProperty(
        name="Viewport Samples",
        description="Samples per pixel of the rendered viewport (0: refine until stopped)",
        default=1024,
        min=0,
        soft_max=4096,
    )
    preview_max_bounces: IntProperty(
        name="Viewport Max Bounces",
        description="Maximum number of times a path scatters in the rendered viewport and in material "
        "previews (lower than a final render's: a faster first image)",
        default=4,
        min=0,
        max=1024,
        soft_max=64,
    )
    preview_pause: BoolProperty(
        name="Pause Preview",
        description="Pause the rendered viewport (changes are applied when it resumes)",
        default=False,
    )
    max_bounces: IntProperty(
        name="Max Bounces",
        description="Maximum number of times a path scatters before it is ended",
        default=8,
        min=0,
        max=1024,
        soft_max=64,
    )
    transparent_max_bounces: IntProperty(
        name="Transparent Max Bounces",
        description="Maximum number of cut-outs (Transparent BSDF, alpha) and films a path goes straight through "
        "(one more, as Cycles counts them); they do not use up Max Bounces, and volumes' boundaries count as neither",
        default=8,
        min=0,
        max=1024,
        soft_max=64,
    )
    seed: IntProperty(
        name="Seed",
        description="Seed of the random numbers: the same seed renders the same image",
        default=0,
        min=0,
    )
    wavelength_mode: EnumProperty(
        name="Wavelength Mode",
        description="How wavelengths are chosen for each path",
        items=WAVELENGTH_MODE_ITEMS,
        default="CIE",
    )
    wavelengths_per_path: IntProperty(
        name="Wavelengths per Path",
        description="Hero wavelengths carried by each path in CIE mode (a dispersive event keeps only the first)",
        default=4,
        min=1,
        max=16,
    )
    mean_r_nm: _mean("R", 600.0)
    sigma_r_nm: _sigma("R", 25.0)
    mean_g_nm: _mean("G", 550.0)
    sigma_g_nm: _sigma("G", 25.0)
    mean_b_nm: _mean("B", 450.0)
    sigma_b_nm: _sigma("B", 15.0)
    use_mis: BoolProperty(
        name="Multiple Importance Sampling",
        description="Combine light sampling and BSDF sampling (less noise from small or bright lights)",
        default=True,
    )
    russian_roulette_depth: IntProperty(
        name="Russian Roulette Depth",
        description="Bounce after which dim paths may be ended at random (unbiased, saves time)",
        default=3,
        min=0,
        soft_max=64,
        max=1024,
    )
    light_tracing: EnumProperty(
        name="Light Tracing",
        description="Caustics (light focused by glass or mirrors onto other surfaces) traced from the lights "
        "and connected to the camera, where path tracing alone stays speckled",
        items=[
            ("AUTO", "Auto", "Trace caustics from the lights where a smooth glass or mirror can focus a light onto "
             "another surface (the render stats say what was chosen)", 0),
            ("OFF", "Off", "Path tracing only", 1),
            ("ON", "On", "Trace caustics from the lights whenever the scene has a specular surface, soap films "
             "included (not through a real lens)", 2),
        ],
        default="AUTO",
    )
    pixel_filter: EnumProperty(
        name="Pixel Filter",
        description="How samples spread over and around their pixel",
        items=[
            ("BOX", "Box", "Samples uniform over the pixel: sharpest, may alias", 0),
            ("GAUSSIAN", "Gaussian", "Samples in a Gaussian around the pixel centre: smoother edges", 1),
        ],
        default="BOX",
    )
    filter_width_px: FloatProperty(
        name="Filter Width",
        description="Gaussian filter: distance in pixels at which it is cut off (standard deviation = width / 3)",
        default=1.5,
        min=0.01,
        soft_max=3.0,
        max=10.0,
        subtype="PIXEL",
    )
    threads: IntProperty(
        name="Threads",
        description="Number of CPU threads to render with (0 = all cores; more than the cores run one per core)",
        default=0,
        min=0,
        max=1024,
    )
    use_pass_variance: BoolProperty(
        name="Noise",
        description="Add a Noise pass: per-pixel variance of the mean (R, G, B)",
        default=False,
        update=_update_render_passes,
    )
    use_pass_sample_count: BoolProperty(
        name="Sample Count",
        description="Add a Sample Count pass: samples accumulated in each pixel",
        default=False,
        update=_update_render_passes,
    )
    use_pass_denoising_data: BoolProperty(
        name="Denoising Data",
        description="Add the Denoising Albedo, Denoising Normal and Denoising Depth passes, the guides of the "
        "compositor's Denoise node",
        default=False,
        update=_update_render_passes,
    )
    use_denoising: BoolProperty(
        name="Denoise",
        description="Denoise the final frame with OpenImageDenoise (as the compositor's Denoise node does), "
        "guided by the albedo and normal; the raw image is kept in the Noisy Image pass",
        default=False,
        update=_update_render_passes,
    )
    denoising_prefilter: EnumProperty(
        name="Prefilter",
        description="How the denoiser treats its albedo and normal guides",
        items=[
            ("NONE", "None", "The guides are used as they are (for noise-free guides)", 0),
            ("FAST", "Fast", "The guides are denoised together with the image", 1),
            ("ACCURATE", "Accurate", "The guides are denoised first (best for noisy guides, takes longer)", 2),
        ],
        default="ACCURATE",
    )
    denoising_quality: EnumProperty(
        name="Quality",
        description="Denoising quality against speed",
        items=[
            ("HIGH", "High", "Best quality", 0),
            ("BALANCED", "Balanced", "Balanced quality and speed", 1),
            ("FAST", "Fast", "Fastest", 2),
        ],
        default="HIGH",
    )
    use_adaptive_sampling: BoolProperty(
        name="Noise Threshold",
        description="Stop sampling pixels whose noise is below the threshold (adaptive sampling)",
        default=False,
    )
    adaptive_threshold: FloatProperty(
        name="Noise Threshold",
        description="Relative noise at which a pixel stops sampling: lower is cleaner and slower (0.01 is typical)",
        default=0.01,
        min=0.0001,
        max=0.9999,
        soft_max=0.1,
        precision=4,
    )
    adaptive_min_samples: IntProperty(
        name="Min Samples",
        description="Samples every pixel takes before it may stop (0 = automatic)",
        default=0,
        min=0,
        soft_max=4096,
    )
    time_limit: FloatProperty(
        name="Time Limit",
        description="Stop sampling after this time (scene preparation excluded; 0 = no limit)",
        default=0.0,
        min=0.0,
        subtype="TIME_ABSOLUTE",
        unit="TIME_ABSOLUTE",
    )
    use_auto_tile: BoolProperty(
        name="Use Tiling",
        description="Render frames larger than the tile size tile by tile, each to all its samples, so Prism "
        "keeps one tile in memory at a time",
        default=True,
    )
    tile_size: IntProperty(
        name="Tile Size",
        description="Side of a tile in pixels",
        default=2048,
        min=8,
        max=16384,
        subtype="PIXEL",
    )
    use_spectral_output: BoolProperty(
        name="Spectral Output",
        description="Also write a multispectral EXR (radiance in wavelength bands across 360-830 nm, the "
        "layout of Fichet et al. 2021) when a render finishes",
        default=False,
    )
    spectral_band_nm: FloatProperty(
        name="Band Width",
        description="Width of the spectral EXR's wavelength bands in nm (adjusted to tile 360-830 nm evenly: "
        "10 nm gives 47 bands)",
        default=10.0,
        min=1.0,
        max=100.0,
        subtype=WAVELENGTH_SUBTYPE,
    )
    spectral_output_path: StringProperty(
        name="File",
        description="Where the spectral EXR is written (// is the .blend file's folder; # becomes the frame "
        "number)",
        default="//spectral_####.exr",
        subtype="FILE_PATH",
        options=BLEND_RELATIVE_PATH_OPTIONS,
    )
    lens_overlay: PointerProperty(
        type=PrismLensOverlaySettings,
        name="Lens Overlay",
        description="Settings of the viewport overlay that draws ray fans through the camera's real lens",
    )
    farm: PointerProperty(
        type=PrismFarmSettings,
        name="Farm",
        description="Where and how the Farm panel submits this scene to a Flamenco render farm",
    )

    def channel_means_nm(self) -> tuple[float, float, float]:
        """(R, G, B) Gaussian means in nm."""
        return (self.mean_r_nm, self.mean_g_nm, self.mean_b_nm)

    def channel_sigmas_nm(self) -> tuple[float, float, float]:
        """(R, G, B) Gaussian standard deviations in nm."""
        return (self.sigma_r_nm, self.sigma_g_nm, self.sigma_b_nm)


def register():
    register_group(PrismSceneSettings, bpy.types.Scene, "prism", "Prism render settings")


def unregister():
    unregister_group(PrismSceneSettings, bpy.types.Scene, "prism")
