"""What the parity runs found, in words: read by report.py into docs/parity.md (per scene, and
"general" for the findings section). The measured numbers live in the generated table, not here."""

FINDINGS: dict[str, str] = {
    "general": """\
- **Animated lights in Render Animation (fixed).** The first run of `frame_range` measured a ratio of
  1.339: Prism rendered frames 2, 4 and 6 all at the bulb's power of frame 1. The export read every light's
  settings from the *original* data-block (so that a script's edit counts even before the depsgraph copies
  it), but Render Animation evaluates its own depsgraph per frame and leaves the original at the current
  frame; Cycles reads the evaluated copy and is right. `engine/export/lights.py` now reads an animated or
  driven light from the evaluated copy (the original otherwise): 0.9999.
- **Animated node values in Render Animation (fixed).** The same cause for materials and the world:
  in `animated_shading` an emissive card's Strength and the world's Strength are keyframed, and Prism
  rendered every frame with frame 1's values (ratio 0.495). Batch renders through `render.py --frames`
  were not affected (they `frame_set` each frame, which writes the animated values into the originals);
  Blender's own Render Animation (Ctrl F12) was. Lights, materials and the world now share one rule
  (`engine/export/animated.py`): the evaluated copy where the data-block or its node tree is animated or
  driven, the original otherwise; the world is read from the evaluated scene.
- **View Layer ▸ Filter ▸ Surfaces (warned).** Prism rendered every surface with the filter off (ratio
  0.94 here only because the floor and world happen to be similar greys); Cycles renders the world alone.
  Filtering is not a small change (Prism refuses a scene with no geometry), so the export now prints a
  warning naming the view layer, the setting and what is rendered instead.
- Everything else matches Cycles to well within the tolerance (|ratio − 1| ≤ 0.5 %, within each scene's
  noise), including the settings issue 32 found silent before: clip range, Environment filter, soft
  falloff, linked libraries, materials without an output.
- Not exercised: view-layer filters for hair (Strands), volumes and per-layer motion blur; Cycles' light
  tree and Prism's light sampling are compared only through mean luminance.
""",
    "soft_falloff": """\
This scene is the noisiest (a point light whose sphere the floor cuts: each engine's sampling of the
lit disc under it is noisy): at 16 samples the ratio's seed-to-seed σ was 1.1 %, too close to the 2 %
tolerance, so it renders 256 samples (σ ≈ 0.2 %, "Noise").""",
    "motion_blur": """\
Prism has no motion blur yet: the ball renders sharp at frame 1 and the warning says so. The ratio is
near 1 because blurring moves light, it does not add any.""",
    "surfaces_filter": """\
Cycles shows the world alone (no surface is seen or casts a shadow); Prism renders the surfaces and
prints the warning above.""",
    "animated_shading": """\
Fixed: see Findings, "Animated node values in Render Animation".""",
}
