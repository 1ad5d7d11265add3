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
- **View Layer ▸ Filter ▸ Surfaces (fixed).** Prism rendered every surface with the filter off and said so
  in a warning; Cycles' Blender sync gives a mesh no triangles then, and renders the world alone. The
  export now reads the layer's Filter as Cycles does (`engine/export/view_layer_filter.py`): Surfaces off
  leaves out every mesh (and the volumes inside them), Curves off every hair curve, and the layer's Motion
  Blur switch joins Render ▸ Motion Blur. A layer left with the world alone renders it (1.0000 of Cycles);
  one left with a black world is refused, naming the filter. The panel is shown for Prism now.
- Everything else matches Cycles to well within the tolerance (|ratio − 1| ≤ 0.5 %, within each scene's
  noise), including the settings issue 32 found silent before: clip range, Environment filter, soft
  falloff, linked libraries, materials without an output.
- Not exercised: the Volumes filter (this comparison was made before Prism rendered Volume objects); Cycles' light
  tree and Prism's light sampling are compared only through mean luminance.
""",
    "soft_falloff": """\
This scene is the noisiest (a point light whose sphere the floor cuts: each engine's sampling of the
lit disc under it is noisy): at 16 samples the ratio's seed-to-seed σ was 1.1 %, too close to the 2 %
tolerance, so it renders 256 samples (σ ≈ 0.2 %, "Noise").""",
    "light_temperature": """\
Mean luminance alone would not see the temperature: a blackbody of luminance 1 lights a grey scene as brightly
as white light, and before Prism read the checkbox (it warned and rendered white) this scene's ratio was 1.0028
(measured on 469ef8b); relMSE, which sees the colour, was 0.83 then. `tests/blender/test_light_temperature.py` holds the colour per channel against Cycles (white
lights, within 1 %) and against the filtered spectrum's closed form (a coloured light).""",
    "motion_blur": """\
Both engines blur the ball over the half-frame shutter (`docs/motion_blur.md`); blurring moves light and
adds none, so the ratio alone would not see a sharp ball: relMSE does, and `tests/blender/test_motion_blur.py`
measures the smear against its closed form.""",
    "layer_motion_blur": """\
Render ▸ Motion Blur is on but this view layer's own switch is off: both engines render the ball sharp
(`tests/blender/test_view_layer_filter.py` checks that no shutter is sampled).""",
    "surfaces_filter": """\
Every surface is left out: the world alone is seen and the bulb lights nothing.""",
    "curves_filter": """\
The glowing tuft of hair curves is left out (with the filter on it raises the mean by 9 %, so the ratio
sees it).""",
    "animated_shading": """\
Fixed: see Findings, "Animated node values in Render Animation".""",
}
