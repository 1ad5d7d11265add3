"""Scene analysis: decide before tracing what the scene needs, and say so in one line.

- Hero-wavelength termination only if a used glass disperses or the camera does (a real lens);
  otherwise every path carries all its wavelengths to the end.
- Emissive meshes are light-sampled only if some used material emits.
- Shadow rays cross free-standing films only if the scene has one (else one occlusion query each).
- Wavelength sampling (cie mode) follows the scene's emission spectra; the visible density only when
  nothing emits.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class SceneAnalysis:
    wavelength_mode: str
    wavelengths_per_path: int
    used_materials: list[int]
    dispersion: bool = False
    dispersive: list[str] = field(default_factory=list)
    camera_disperses: bool = False
    mesh_lights: bool = False
    light_kinds: list[str] = field(default_factory=list)
    features: list[str] = field(default_factory=list)
    world: str = ""
    guided_lines: int = 0
    guided_measured: int = 0
    guided_smooth: int = 0
    camera_strategy: str = ""
    see_through_films: bool = False
    sampler: str = "sobol"

    def strategy(self, use_mis: bool, pixel_filter: str) -> str:
        """One line for the render stats."""
        parts = [f"{self.wavelength_mode} x{self.wavelengths_per_path}"]
        counts = ((self.guided_lines, "emission line(s)"), (self.guided_measured, "measured spectrum(s)"),
                  (self.guided_smooth, "smooth spectrum(s)"))
        guides = [f"{count} {what}" for count, what in counts if count]
        if guides:
            parts[0] += " guided by " + " + ".join(guides)
        if self.dispersion:
            what = ", ".join(self.dispersive + (["lens"] if self.camera_disperses else []))
            parts.append(f"hero-wavelength termination ({what})")
        else:
            parts.append("no dispersion: all wavelengths kept")
        lights = ", ".join(sorted(set(k for k in self.light_kinds if k != "emissive meshes"))) or "none"
        parts.append(f"lights: {lights}" + (" + emissive meshes" if self.mesh_lights else ""))
        if self.world:
            parts.append(self.world)
        parts.append("NEE+BSDF MIS" if use_mis else "NEE only (no MIS)")
        if self.see_through_films:
            parts.append("see-through film shadows")
        if self.features:
            parts.append("materials: " + ", ".join(self.features))
        parts.append(f"{pixel_filter} filter")
        parts.append(f"{self.sampler} sampler")
        if self.camera_strategy:
            parts.append(self.camera_strategy)
        return " | ".join(parts)
