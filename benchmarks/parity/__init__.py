"""Scene parity with Cycles (issue 32): small scenes built by script, each exercising one of Blender's
scene settings (clip range, view-layer filters, soft falloff, instancing, linked libraries, materials
without an output, holdouts, ray visibility, alpha, view layers, render border, resolution percentage,
pixel aspect, frame range), rendered by Prism and by Cycles through the bpy module and compared in
absolute terms. ``python -m benchmarks.parity.run`` (``make parity``) writes docs/parity.md;
tests/blender/test_parity.py asserts each scene's verdict.

| file | what |
|---|---|
| `record.py` | `ParityScene` (one scene), `EngineImage`, `ParityResult` and its verdict, the 2 % tolerance |
| `building.py` | bpy builders the scenes share (materials, planes, spheres, lights, camera, world, the stage) |
| `scenes_objects.py`, `scenes_output.py` | the scenes: what is rendered and how it is seen; film and output |
| `catalogue.py` | every scene in the report's order |
| `engines.py`, `exr_files.py` | rendering with Prism (warnings captured) and Cycles, reading the EXRs back |
| `metrics.py`, `pictures.py` | luminance ratio, relMSE, alpha difference; the Prism | Cycles PNGs |
| `compare.py`, `noise.py` | one scene compared; the seed-to-seed spread of its ratio |
| `report.py`, `run.py` | docs/parity.md; the command line |
"""
