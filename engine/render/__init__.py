"""One render, F12 or batch, on Blender's side: the ``RenderEngine`` Blender calls (``render_engine``), the
session that exports, renders and fills the Render Result (``session``), what a caller asks and is told
(``request``), the status line (``stats``), the passes registered and written (``result_passes``), and
what makes farm chunks of one render mergeable (``fingerprint``, ``chunks``)."""
