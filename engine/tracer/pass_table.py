"""Render passes, declared once: what each film buffer holds and how each Blender pass is made from them.

A **film buffer** is a per-pixel accumulator next to Combined: ``width`` float64 channels summed over
the pixel's samples (the pass is their mean). A depth buffer holds the depth of the samples that hit a
surface and their number, so a pixel's depth is the mean over its surface samples (its centre's depth
inside a surface, as Cycles writes it), never a blend of a near surface and the background. A
``spectral`` buffer is
filled per wavelength by the stage kernels and turned into Rec.709 once per path by the film stage
(``stages.pass_writes``), like Combined. Reflectances (albedos, colours) are carried as reflectance × the
spectrum of a white emitter, so a white surface reads (1, 1, 1).

A **pass** is what Blender receives: its name and channels (Cycles' names and meanings) and the
buffers it is computed from. Adding a pass = one ``Buffer`` (if it needs new data) + one ``Pass``.

The kernels see only ``PassLayout`` (``layout``): for each kind of data the column or spectral slot it
goes to, -1 when nobody asked for it, so a render with Combined alone does no pass work at all.
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from .cryptomatte import CHANNELS as CRYPTOMATTE_CHANNELS
from .cryptomatte import DEFAULT_LEVELS
from .cryptomatte import KINDS as CRYPTOMATTE_KINDS
from .cryptomatte import pass_names as cryptomatte_pass_names
from .cryptomatte_film import COLUMNS as CRYPTOMATTE_COLUMNS
from .shadow_catcher_film import WIDTH as CATCHER_WIDTH

BACKGROUND_DEPTH_M = 1e10  # Depth of pixels that see no surface (Blender's value)


@dataclass(frozen=True)
class Buffer:
    key: str
    width: int = 3
    spectral: bool = False


#: Light that reached the camera, split by what it did first (see ``stages.pass_writes``).
LIGHT_SLOTS = ("emission", "environment", "diffuse_direct", "diffuse_indirect", "glossy_direct", "glossy_indirect",
               "transmission_direct", "transmission_indirect", "diffuse_color", "glossy_color", "transmission_color")
#: The light slots Film ▸ Exposure scales: light, not the albedo-like colour passes.
EXPOSED_BUFFERS = frozenset(slot for slot in LIGHT_SLOTS if not slot.endswith("_color"))

BUFFERS = {b.key: b for b in (
    Buffer("depth", 2),  # depth of a sample on a surface (m), 1 for such a sample
    Buffer("position"),
    Buffer("normal"),
    Buffer("denoising_normal"),
    Buffer("denoising_depth", 2),
    Buffer("denoising_albedo", spectral=True),
    Buffer("mist", 1),  # 1 - mist of the surface first seen (the pass is 1 - the mean: 1 where none)
    Buffer("object_index", 2),  # pass index of sample 0's object and 1 (sample 0 only: Cycles overwrites)
    Buffer("material_index", 2),  # the same for its material
    Buffer("uv"),  # u, v, 1 of the first surface's render UV map
    Buffer("ao", 1),  # 1 where the first surface's ambient-occlusion ray is free
    Buffer("vector", 5),  # the first surface's motion in pixels to the previous / from the next frame, and 1
    Buffer("shadow_catcher", CATCHER_WIDTH),  # the shadow catcher's accumulations (``shadow_catcher_film``)

    *(Buffer(key, spectral=True) for key in LIGHT_SLOTS),
)}


#: How a pass is made from its buffer's per-pixel mean (``Pass.reduce``): the mean itself; DEPTH: sum /
#: count (the buffer's last channel), 1e10 where no sample counted; FIRST: the same, 0 where none (values
#: of sample 0 only); SURFACE: the same, 0 where none (the mean over the samples that hit a surface, as
#: Cycles divides its Vector pass by its motion weight); COMPLEMENT: 1 - the mean; GREY: a 1-wide mean as
#: R = G = B; CATCHER: Cycles' shadow catcher ratio, made with Combined by ``shadow_catcher_film`` (the film
#: writes it, not ``FilmLayout.images``).
MEAN, DEPTH, FIRST, SURFACE, COMPLEMENT, GREY, CATCHER = ("mean", "depth", "first", "surface", "complement", "grey",
                                                          "catcher")


@dataclass(frozen=True)
class Pass:
    """A Blender pass: ``name``, ``channels`` (ids, e.g. "XYZ"), ``kind`` (VALUE / VECTOR / COLOR), the
    ``buffers`` it reads and, for light passes, the colour buffer it is divided by (Cycles' convention:
    Direct and Indirect hold light without the surface colour, so (Direct + Indirect) × Color is the
    light of that lobe in Combined)."""

    name: str
    channels: str
    kind: str
    buffer: str
    divide_by: str | None = None
    meaning: str = ""
    reduce: str = MEAN


PASSES = {p.name: p for p in (
    Pass("Depth", "Z", "VALUE", "depth", meaning="distance along the camera's view axis to the surfaces seen "
         "in the pixel (m, their mean); 1e10 where none", reduce=DEPTH),
    Pass("Mist", "Z", "VALUE", "mist", meaning="World ▸ Mist Pass of the surface first seen: ((distance - "
         "start) / depth) clamped to 0-1, raised to the falloff; 1 where none", reduce=COMPLEMENT),
    Pass("Position", "XYZ", "VECTOR", "position", meaning="world position of the surface first seen (m)"),
    Pass("Normal", "XYZ", "VECTOR", "normal", meaning="world-space shading normal of the surface first seen, "
         "facing the camera"),
    Pass("Vector", "XYZW", "VECTOR", "vector", meaning="motion of the surface first seen, in pixels (x right, y "
         "up): X, Y = its position in the previous frame - now, Z, W = now - in the next frame (camera motion "
         "included); the mean over the samples that hit a surface, 0 where none; 0 with Render ▸ Motion Blur "
         "on, as Cycles", reduce=SURFACE),
    Pass("UV", "UVA", "VECTOR", "uv", meaning="the render UV map of the surface first seen (u, v, 1; 0 where "
         "none or without UV map)"),
    Pass("IndexOB", "X", "VALUE", "object_index", meaning="Object ▸ Relations ▸ Pass Index of the object sample "
         "0 of the pixel saw first (not averaged); 0 where none", reduce=FIRST),
    Pass("IndexMA", "X", "VALUE", "material_index", meaning="Material ▸ Settings ▸ Pass Index of that "
         "surface's material", reduce=FIRST),
    Pass("AO", "RGB", "COLOR", "ao", meaning="ambient occlusion of the surface first seen: the fraction of "
         "cosine-weighted directions free within World ▸ Ambient Occlusion ▸ Distance", reduce=GREY),
    Pass("Denoising Normal", "XYZ", "VECTOR", "denoising_normal", meaning="camera-space shading normal (x right, "
         "y up, z forward) of the first surface that is not a perfect mirror or glass; 0 where none"),
    Pass("Denoising Albedo", "RGB", "COLOR", "denoising_albedo", meaning="albedo of that surface seen through "
         "the mirrors and glass in front of it; the radiance of the background or light where no surface"),
    Pass("Denoising Depth", "Z", "VALUE", "denoising_depth", meaning="distance along the view axis to that "
         "surface (m); 1e10 where none", reduce=DEPTH),
    Pass("Emit", "RGB", "COLOR", "emission", meaning="emission of surfaces seen directly"),
    Pass("Env", "RGB", "COLOR", "environment", meaning="the world seen directly"),
    Pass("DiffDir", "RGB", "COLOR", "diffuse_direct", "diffuse_color", "light reaching the camera after one "
         "diffuse scattering, divided by Diffuse Color"),
    Pass("DiffInd", "RGB", "COLOR", "diffuse_indirect", "diffuse_color", "light after a first diffuse "
         "scattering and more bounces, divided by Diffuse Color"),
    Pass("DiffCol", "RGB", "COLOR", "diffuse_color", meaning="albedo of the diffuse lobes of the surface first seen"),
    Pass("GlossDir", "RGB", "COLOR", "glossy_direct", "glossy_color"),
    Pass("GlossInd", "RGB", "COLOR", "glossy_indirect", "glossy_color"),
    Pass("GlossCol", "RGB", "COLOR", "glossy_color", meaning="reflectance of the glossy and mirror lobes"),
    Pass("TransDir", "RGB", "COLOR", "transmission_direct", "transmission_color"),
    Pass("TransInd", "RGB", "COLOR", "transmission_indirect", "transmission_color"),
    Pass("TransCol", "RGB", "COLOR", "transmission_color", meaning="transmittance of the refracting lobes"),
    Pass("Shadow Catcher", "RGB", "COLOR", "shadow_catcher", meaning="on shadow catchers, their light with the "
         "other objects divided by their light without them (below 1 in shadows); 1 elsewhere",
         reduce=CATCHER),
)}

#: Blender's view-layer switch of each pass (``ViewLayer.use_pass_*``), for the Blender side.
VIEW_LAYER_SWITCH = {
    "Depth": "use_pass_z", "Mist": "use_pass_mist", "Position": "use_pass_position", "Normal": "use_pass_normal",
    "Vector": "use_pass_vector",
    "UV": "use_pass_uv", "IndexOB": "use_pass_object_index", "IndexMA": "use_pass_material_index",
    "AO": "use_pass_ambient_occlusion", "Emit": "use_pass_emit",
    "Env": "use_pass_environment", "DiffDir": "use_pass_diffuse_direct", "DiffInd": "use_pass_diffuse_indirect",
    "DiffCol": "use_pass_diffuse_color", "GlossDir": "use_pass_glossy_direct",
    "GlossInd": "use_pass_glossy_indirect", "GlossCol": "use_pass_glossy_color",
    "TransDir": "use_pass_transmission_direct", "TransInd": "use_pass_transmission_indirect",
    "TransCol": "use_pass_transmission_color",
}
#: Passes whose switch is in Cycles' view-layer settings (``ViewLayer.cycles``), for the Blender side.
CYCLES_VIEW_LAYER_SWITCH = {"Shadow Catcher": "use_pass_shadow_catcher"}
DENOISING_PASSES = ("Denoising Normal", "Denoising Albedo", "Denoising Depth")
LIGHT_GROUP_PREFIX = "Combined_"


@dataclass
class PassRequest:
    """What a render should produce besides Combined: pass names (keys of ``PASSES``), light group names
    (a ``Combined_<name>`` pass each) and shader AOVs (name → "VALUE" or "COLOR")."""

    passes: tuple[str, ...] = ()
    light_groups: tuple[str, ...] = ()
    aovs: dict[str, str] = field(default_factory=dict)
    cryptomatte: tuple[str, ...] = ()  # kinds of ``cryptomatte.KINDS`` (Object, Material, Asset)
    cryptomatte_levels: int = DEFAULT_LEVELS

    def validate(self) -> None:
        from .errors import PrismInputError

        for name in self.passes:
            if name not in PASSES:
                raise PrismInputError(f"Render pass '{name}' is unknown: use one of {', '.join(PASSES)}.")
        for kind in self.cryptomatte:
            if kind not in CRYPTOMATTE_KINDS:
                raise PrismInputError(
                    f"Cryptomatte kind '{kind}' is unknown: use one of {', '.join(CRYPTOMATTE_KINDS)}.")
        if len(set(self.light_groups)) != len(self.light_groups):
            raise PrismInputError("Two light groups have the same name: rename one (View Layer ▸ Light Groups).")

    @property
    def empty(self) -> bool:
        return not (self.passes or self.light_groups or self.aovs or self.cryptomatte)


#: For the kernels: the column (values) or spectral slot of each buffer, -1 when off; ``light`` the
#: first of the LIGHT_SLOTS slots (consecutive); ``group`` / ``groups`` the first light-group slot and
#: their count; ``aov`` / ``aovs`` the first AOV column (4 columns each); ``columns`` / ``slots`` the
#: sizes; ``rgb_column`` where spectral slot s lands (3 columns from rgb_column + 3 s); ``white`` the
#: spectrum id of a white emitter (reflectances are converted through it); ``cryptomatte`` the first of the
#: columns after the film's (object and material index + 1 and weight of the surface a camera sample is
#: attributed to: ``stages.cryptomatte_write``; not summed by the film: ``cryptomatte_film``), -1 when no
#: Cryptomatte pass is on; ``catcher`` the first of the shadow catcher's columns (``shadow_catcher_film``), -1
#: when the scene has no catcher and its pass is off.
PassLayout = namedtuple(
    "PassLayout",
    "depth position normal denoising_normal denoising_depth denoising_albedo light group groups aov aovs "
    "columns slots rgb_column white mist object_index material_index uv ao vector cryptomatte catcher",
)


class FilmLayout:
    """Where every enabled buffer lives in the film's ``aux`` columns, and the kernels' ``PassLayout``.
    ``catcher_objects``: the scene has a shadow catcher (its accumulations are kept, and Combined is made
    from them, as Cycles does, even when its pass is off)."""

    def __init__(self, request: PassRequest, white_spectrum: int = -1, catcher_objects: bool = False):
        request.validate()
        self.request = request
        self.catcher_objects = bool(catcher_objects)
        wanted = {"shadow_catcher"} if catcher_objects else set()
        for name in request.passes:
            p = PASSES[name]
            wanted.add(p.buffer)
            if p.divide_by:
                wanted.add(p.divide_by)
        if wanted & set(LIGHT_SLOTS):
            wanted |= set(LIGHT_SLOTS)  # the light split needs every slot (each is the remainder of the others)
        values = [k for k in BUFFERS if k in wanted and not BUFFERS[k].spectral]
        spectral = [k for k in BUFFERS if k in wanted and BUFFERS[k].spectral]
        self.columns: dict[str, tuple[int, int]] = {}  # buffer or group/aov key -> (first column, width)
        column = 0
        for key in values:
            self.columns[key] = (column, BUFFERS[key].width)
            column += BUFFERS[key].width
        self.aov_names = list(request.aovs)
        aov_column = column
        for name in self.aov_names:
            self.columns["aov:" + name] = (column, 4)
            column += 4
        rgb_column = column
        self.slot_keys = spectral + ["group:" + g for g in request.light_groups]
        for key in self.slot_keys:
            self.columns[key] = (column, 3)
            column += 3
        self.width = column  # the film's columns: the Cryptomatte indices follow them, per sample only
        self.cryptomatte_column = column if request.cryptomatte else -1
        if request.cryptomatte:
            column += CRYPTOMATTE_COLUMNS
        slot = {key: s for s, key in enumerate(self.slot_keys)}
        col = {key: self.columns[key][0] if key in self.columns else -1 for key in BUFFERS}
        groups = len(request.light_groups)
        self.kernel = PassLayout(
            col["depth"], col["position"], col["normal"], col["denoising_normal"], col["denoising_depth"],
            slot.get("denoising_albedo", -1), slot.get(LIGHT_SLOTS[0], -1),
            slot["group:" + request.light_groups[0]] if groups else -1, groups,
            aov_column if self.aov_names else -1, len(self.aov_names), column, len(self.slot_keys), rgb_column,
            int(white_spectrum), col["mist"], col["object_index"], col["material_index"], col["uv"], col["ao"],
            col["vector"], self.cryptomatte_column, col["shadow_catcher"])

    def images(self, aux_mean: np.ndarray, exposure: float = 1.0) -> dict[str, np.ndarray]:
        """Every requested pass from the film's per-pixel ``aux_mean`` [..., width] (sums divided by the
        sample count): name → float32 [..., channels]. ``exposure`` (Film ▸ Exposure) scales the light
        passes and light groups, as Cycles does; data and colour (albedo) passes stay as they are."""
        out = {}
        for name in self.request.passes:
            p = PASSES[name]
            if p.reduce == CATCHER:
                continue  # made with Combined (``Film.shadow_catcher``)
            image = self._buffer(aux_mean, p.buffer)
            if p.reduce in (DEPTH, FIRST, SURFACE):  # sums over the samples that counted, and their count
                hits = image[..., -1:]
                empty = BACKGROUND_DEPTH_M if p.reduce == DEPTH else 0.0
                image = np.divide(image[..., :-1], hits, out=np.full_like(image[..., :-1], empty), where=hits > 0)
            elif p.reduce == COMPLEMENT:
                image = 1.0 - image
            elif p.reduce == GREY:
                image = np.repeat(image, 3, axis=-1)
            elif p.divide_by:
                colour = self._buffer(aux_mean, p.divide_by)
                image = np.divide(image, colour, out=np.zeros_like(image), where=colour > 1e-8)
            if p.buffer in EXPOSED_BUFFERS:
                image = image * exposure
            out[name] = image.astype(np.float32)
        for group in self.request.light_groups:
            out[LIGHT_GROUP_PREFIX + group] = (self._buffer(aux_mean, "group:" + group) * exposure).astype(np.float32)
        for name, kind in self.request.aovs.items():
            first, _ = self.columns["aov:" + name]
            width = 1 if kind == "VALUE" else 4
            out[name] = aux_mean[..., first:first + width].astype(np.float32)
        return out

    def _buffer(self, aux_mean, key):
        first, width = self.columns[key]
        return aux_mean[..., first:first + width]


def aov_table(materials, aovs: dict) -> np.ndarray:
    """[materials, AOVs, 4]: what each material writes into each AOV pass (colour: r, g, b, 1; value:
    value, 0, 0, 0); 0 where a material has no AOV Output of that name."""
    table = np.zeros((max(1, len(materials)), len(aovs), 4))
    for m, material in enumerate(materials):
        for a, (name, kind) in enumerate(aovs.items()):
            if name in material.aovs:
                r, g, b, value = material.aovs[name]
                table[m, a] = (value, 0.0, 0.0, 0.0) if kind == "VALUE" else (r, g, b, 1.0)
    return table


def aov_registers(materials, aovs: dict) -> np.ndarray:
    """int32 [materials, AOVs, 2]: where each material's program leaves an AOV that varies per hit (its
    AOV Output's linked socket): the first register and how many (3 for a colour AOV's r, g, b, 1 for a value
    AOV); -1, 0 where the AOV is a constant of ``aov_table``."""
    table = np.zeros((max(1, len(materials)), len(aovs), 2), np.int32)
    table[..., 0] = -1
    for m, material in enumerate(materials):
        shader = getattr(material, "shader", None)
        registers = shader.aov_registers if shader is not None else {}
        for a, (name, kind) in enumerate(aovs.items()):
            socket = "Value" if kind == "VALUE" else "Color"
            if socket in registers.get(name, {}):
                table[m, a] = (registers[name][socket], 1 if kind == "VALUE" else 3)
    return table


def blender_passes(request: PassRequest) -> list[tuple[str, str, str]]:
    """(name, channel ids, kind) of every pass ``request`` produces besides Combined, in Blender's order."""
    out = [(name, PASSES[name].channels, PASSES[name].kind) for name in PASSES if name in request.passes]
    out += [(name, "X" if kind == "VALUE" else "RGBA", kind) for name, kind in request.aovs.items()]
    out += [(LIGHT_GROUP_PREFIX + g, "RGB", "COLOR") for g in request.light_groups]
    out += [(name, CRYPTOMATTE_CHANNELS, "COLOR") for kind in CRYPTOMATTE_KINDS if kind in request.cryptomatte
            for name in cryptomatte_pass_names(kind, request.cryptomatte_levels)]
    return out
