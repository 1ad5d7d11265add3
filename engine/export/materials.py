"""Blender materials → ``tracer.scene.Material``: the node tree compiled as Cycles reads it (``nodes``),
with ``Material.prism`` adding glass dispersion, measured metals, coatings and free-standing films.

A material without nodes renders its viewport colour (as Cycles does); a free-standing thin film
(Material ▸ Prism ▸ Thin Film) replaces the node tree. What Prism leaves out or approximates becomes one
warning per material, node and message. One ``MaterialExporter`` serves a whole export: it numbers the
UV maps and attributes the programs read and shares the images they decode.
"""

from __future__ import annotations

import math

from ..properties.principled import surface_node
from ..tracer.bsdf.closure import CONDUCTOR, DIELECTRIC, FRESNEL_CONDUCTOR, FRESNEL_F82
from ..tracer.errors import PrismInputError
from ..tracer.data_passes import AO_DISTANCE_DEFAULT
from ..tracer.scene import Material, SpectrumSpec
from .animated import settings_source
from .aovs import merge_compiled, read_aovs
from .nodes import AttributeSlots, compile_material
from .nodes.overrides import check_film
from .spectra import material_emission_source, material_reflectance_source
from .texture_memory import TextureCache

DEFAULT_MATERIAL = Material(name="Default", kind="diffuse", base_color=(0.8, 0.8, 0.8))


def _viewport_material(material, reflectance) -> Material:
    """A material without nodes: its viewport display colour (or ``reflectance``, the measured one that
    replaces it), metallic and roughness (as Cycles)."""
    colour = tuple(float(c) for c in material.diffuse_color[:3])
    if not all(math.isfinite(c) and c >= 0 for c in colour):
        raise PrismInputError(f"Material '{material.name}': a colour is negative, NaN or infinite; pick a colour again.")
    kind = "conductor" if material.metallic >= 0.5 else "diffuse"
    return Material(name=material.name, kind=kind, base_color=tuple(min(c, 1.0) for c in colour),
                    roughness=min(max(float(material.roughness), 0.0), 1.0), reflectance=reflectance)


def _measured_reflectance(material, settings):
    """Material ▸ Prism's measured reflectance (``scene.ReflectanceSpec``), or None for the RGB base colour."""
    if settings is None or settings.reflectance_source == "COLOR":
        return None
    return material_reflectance_source(material, (0.0, 0.0, 0.0)).spec()


def _thin_film(material, settings) -> Material:
    exported = Material(name=material.name, kind="thin_film", film_thickness_nm=float(settings.film_thickness_nm),
                        film_ior=float(settings.film_ior))
    check_film(material.name, "Material ▸ Prism ▸ Film Thickness", exported.film_thickness_nm,
               "Material ▸ Prism ▸ Film IOR", exported.film_ior)
    return exported


def _summary(material, compiled) -> Material:
    """The tracer material carrying ``compiled.shader``, its other fields describing it for messages."""
    shader = compiled.shader
    closures = shader.closures if shader is not None else []
    kinds = [spec.kind for spec in closures]
    metal = any(spec.kind == CONDUCTOR and spec.fresnel in (FRESNEL_F82, FRESNEL_CONDUCTOR) for spec in closures)
    kind = "dielectric" if DIELECTRIC in kinds else ("conductor" if metal else "diffuse")
    exported = Material(name=material.name, kind=kind, shader=shader, medium=compiled.medium)
    if shader is None:  # no Material Output (an add-on's node tree): black, as Cycles and the warning say
        exported.base_color = (0.0, 0.0, 0.0)
    for spec in closures:
        if spec.kind in (DIELECTRIC, CONDUCTOR) and (kind != "diffuse"):
            exported.roughness = math.sqrt(max(spec.alpha, 0.0))
            exported.ior = spec.eta
            if spec.s0 is not None and spec.s0.rgb is not None and spec.kind == CONDUCTOR:
                exported.base_color = tuple(spec.s0.rgb)
            exported.coating_thickness_nm, exported.coating_ior = spec.coat_nm, spec.coat_ior
            if (spec.kind == DIELECTRIC) == (kind == "dielectric"):
                break
    if compiled.glass is not None:
        source, value = compiled.glass
        if source == "catalogue":
            exported.glass = value
        else:
            exported.glass_nd, exported.glass_vd = value
    exported.conductor = compiled.conductor
    if shader is not None and shader.emission is not None and shader.emission_strength > 0:
        emission = shader.emission
        exported.emission_strength = float(shader.emission_strength)
        if emission.rgb is not None:
            exported.emission = SpectrumSpec(kind="rgb", rgb=tuple(emission.rgb))
        elif isinstance(emission.spectrum, SpectrumSpec):
            exported.emission = emission.spectrum
    return exported


class MaterialExporter:
    """Exports the materials of one render; ``slots`` says which mesh data their programs read."""

    def __init__(self, warnings: list[str] | None = None, fold: bool = True, texture_budget=None, ao_distance=None):
        self.warnings = warnings
        # World ▸ Ambient Occlusion ▸ Distance: where an Ambient Occlusion node's own distance is 0 (Cycles).
        self.ao_distance = AO_DISTANCE_DEFAULT if ao_distance is None else float(ao_distance)
        self.slots = AttributeSlots()
        # Image textures are counted against the memory left beside the frame (``texture_memory``).
        self.image_cache: dict = TextureCache(texture_budget) if texture_budget is not None else {}
        self.needs: dict[str, set] = {}  # material name → what its program reads
        self._fold = fold
        self._evaluate = None

    def _evaluator(self):
        if self._fold and self._evaluate is None:
            from ..tracer.materials.folding import fold_evaluator

            self._evaluate = fold_evaluator()
        return self._evaluate

    def export(self, material) -> Material:
        """The tracer material for a Blender material (None → the default grey diffuse)."""
        if material is None:
            return DEFAULT_MATERIAL
        # The original data-block (what a script set last), or the evaluated one where animated: ``animated``.
        material = settings_source(material)
        settings = getattr(material, "prism", None)
        if settings is not None and settings.is_thin_film:
            if settings.reflectance_source != "COLOR" and self.warnings is not None:
                self.warnings.append(f"Material '{material.name}': a free-standing thin film has no base colour; "
                                     "its measured reflectance (Material ▸ Prism ▸ Base Colour Spectrum) is not "
                                     "used, the film's interference colours render instead.")
            return _thin_film(material, settings)
        reflectance = _measured_reflectance(material, settings)
        if not material.use_nodes or material.node_tree is None:
            return _viewport_material(material, reflectance)
        node = surface_node(material)
        if node is not None and node.bl_idname == "ShaderNodeHoldout":
            return Material(name=material.name, kind="diffuse", base_color=(0.0, 0.0, 0.0), holdout=True)
        overrides = {}
        if reflectance is not None:
            overrides["reflectance"] = reflectance
        if settings is not None and settings.emission_source != "COLOR":
            overrides["emission"] = material_emission_source(material, (1.0, 1.0, 1.0)).spec()
        compiled = compile_material(material, self.slots, self.image_cache, self._evaluator(), overrides=overrides,
                                    ao_distance=self.ao_distance)
        if self.warnings is not None:
            self.warnings.extend(compiled.warnings)
        self.needs[material.name] = compiled.needs
        exported = _summary(material, compiled)
        exported.aovs = merge_compiled(read_aovs(material), compiled.shader)
        exported.reflectance = reflectance  # for messages: the closures carry it (``nodes.measured_base``)
        return exported


def export_material(material, warnings: list[str] | None = None) -> Material:
    """One material on its own (its UV and attribute slots numbered from 0)."""
    return MaterialExporter(warnings).export(material)
