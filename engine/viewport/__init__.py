"""Prism in the 3D viewport's Rendered mode.

- ``progressive``: a Renderer refined by a background thread, changes applied between passes (no bpy).
- ``view``: the viewport's region, view and projection → a tracer camera and border.
- ``scene_sync``: the evaluated depsgraph → tracer scene, re-reading only the meshes that changed.
- ``settings``: the viewport's render settings (samples, bounces, pause).
- ``display``: drawing the latest image in ``view_draw`` (the only gpu calls).
- ``session``: one viewport's session, created by ``view_update`` and stopped when its engine is freed.
"""
