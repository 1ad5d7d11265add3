"""The parts of ``render.py`` (batch renders) that are not Blender calls: its command line,
Ctrl-C handling and the atomic writing of its output files."""
