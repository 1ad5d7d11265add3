"""The light of a Volume object's material: which grid sets its temperature, the box that holds both grids,
and the warning where Prism's glow fills more than Cycles'.

Cycles' Principled Volume multiplies its Temperature by the grid its Temperature Attribute names
("temperature" by default) when the volume has that grid, and otherwise uses the Temperature alone; it
renders only where the object's active voxels are. Prism renders a grid medium inside the box of its voxels,
so light that does not vanish where the grids read 0 (Emission Strength × Color, or blackbody light that
Blackbody Intensity below 1 keeps at 0 K) fills that box evenly.
"""

from __future__ import annotations

import numpy as np

from ..tracer.media.temperature_emission import emission_rows


#: Prism / Cycles 4.5 mean luminance of a 16³ Volume object, every voxel active, unturned and unscaled,
#: glowing at 2000 K without a temperature grid (tools/volume_emission_vs_cycles.py boxconstplain: 1.2050,
#: 2026-12-06); the same light in a mesh cube of the voxels' size: 0.9986 ("cube").
FULL_BOX_GLOW_VS_CYCLES = 1.2


def socket_string(node, name) -> str:
    """A node input's string value (an attribute name), "" where the node has no such input."""
    socket = node.inputs.get(name)
    return str(getattr(socket, "default_value", "") or "") if socket is not None else ""


def temperature_grid_name(name, nodes, grids, notes) -> str | None:
    """The float grid of ``grids`` that the blackbody Principled Volumes of ``nodes`` read as their
    Temperature Attribute, or None (none reads one the file has: the Temperature alone, as in Cycles)."""
    wanted = []
    for node in nodes:
        intensity = node.inputs.get("Blackbody Intensity")
        if node.bl_idname == "ShaderNodeVolumePrincipled" and float(getattr(intensity, "default_value", 0.0)) > 0:
            value = socket_string(node, "Temperature Attribute")
            if value in grids and value not in wanted:
                wanted.append(value)
    if len(wanted) > 1:
        notes.append(f"Volume '{name}': its Principled Volumes read the temperature grids {wanted}; Prism "
                     f"multiplies every Temperature by the first, '{wanted[0]}'.")
    return wanted[0] if wanted else None


def index_box(shape, index_to_object, others=()) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) index corners, in the grid of ``shape`` and ``index_to_object``, of the box holding its
    voxels' bounds (index -1 .. n per axis) and those of ``others``, (shape, index_to_object) pairs."""
    low, high = np.full(3, -1.0), np.asarray(shape, np.float64)
    to_index = np.linalg.inv(index_to_object)
    for other_shape, other_to_object in others:
        corners = np.array([[(c & 1), (c >> 1) & 1, (c >> 2) & 1] for c in range(8)], np.float64)
        corners = corners * (np.asarray(other_shape, np.float64) + 1.0) - 1.0
        placed = (to_index @ other_to_object)[:3, :3] @ corners.T + (to_index @ other_to_object)[:3, 3:4]
        low, high = np.minimum(low, placed.min(1)), np.maximum(high, placed.max(1))
    return low, high


def glow_note(name, spec, density) -> str | None:
    """The warning for a grid medium ``spec`` whose light does not vanish where its grids read 0, or None;
    ``density``: its density grid's voxels (the share of the box they leave empty is named)."""
    if spec.temperature_grid is not None:
        glows = emission_rows(spec)[0][0].max() > 0.0  # the row where the temperature grid reads 0
    else:
        glows = bool(spec.emission)
    if not glows:
        return None
    empty = float(np.mean(np.asarray(density) <= 0.0))
    return (f"Volume '{name}': its material emits light where its grids read 0 (Emission Strength, or blackbody "
            f"light a Blackbody Intensity below 1 keeps at 0 K); Prism fills the box around its voxels with that "
            f"light evenly and Cycles a smaller region (a 16³ grid with every voxel active glows "
            f"{FULL_BOX_GLOW_VS_CYCLES:g} × Cycles' light in Prism), and {100 * empty:.0f} % of this box holds no "
            "density, which Cycles may leave dark too.")
