"""Background kernel warm-up: a separate process compiles the tracer's kernels into the cache when a
scene switches to Prism, so that the first F12 finds them ready.

- ``triggers``: the Blender side (the engine switch, loaded files, registration); imports no numba.
- ``launch``: starts the process (once: ``lock``), says whether one is running, waits for it.
- ``child``: the process itself (run as a script by ``sys.executable``), rendering ``scene``.
"""
