"""Where "Displacement and Bump" is not exactly Cycles': the bump's space on a scaled object.

Cycles computes the bump that "Both" adds in object space (``bump_from_displacement`` with
``use_object_space``): its slope follows the object's scale, as the displaced vertices do. Prism bends the
normal in world space, which is the same for an object of scale 1; for one uniformly scaled by s, Cycles' bump
is s times as steep as Prism's (``svm_node_set_bump``: the normal leans by surface gradient / |det|, and in
object space the differentials are 1/s as long). The vertices themselves move in object space in both.
"""

from __future__ import annotations

import numpy as np

from .nodes.vectors import displacement_method

SCALE_TOLERANCE = 1e-3  # relative: a scale this close to 1 bends the normal as Cycles does


def _uses_both(material) -> bool:
    if material is None or not getattr(material, "use_nodes", False) or material.node_tree is None:
        return False
    if displacement_method(material) != "BOTH":
        return False
    return any(node.bl_idname == "ShaderNodeOutputMaterial" and node.inputs["Displacement"].is_linked
               for node in material.node_tree.nodes)


def both_bump_scale_warning(obj) -> str | None:
    """The warning for mesh ``obj`` whose materials use "Displacement and Bump" while it is scaled; else None."""
    names = [slot.material.name for slot in obj.material_slots if _uses_both(slot.material)]
    if not names:
        return None
    linear = np.array(obj.matrix_world, dtype=np.float64)[:3, :3]
    axes = np.linalg.norm(linear, axis=0)
    if np.allclose(axes, 1.0, rtol=SCALE_TOLERANCE, atol=0.0):
        return None
    scale = float(np.cbrt(abs(np.linalg.det(linear))))
    uniform = np.allclose(axes, axes[0], rtol=SCALE_TOLERANCE, atol=0.0)
    how = (f"Prism's bump is {1.0 / scale:.3g} × as steep as Cycles'" if uniform else
           f"Prism's bump differs from Cycles' by axis (scale {', '.join(f'{a:.3g}' for a in axes)})")
    return (f"Object '{obj.name}' is scaled (× {scale:.3g}) and its material {', '.join(repr(n) for n in names)} uses "
            f"Displacement and Bump: Cycles bends the normal in object space, Prism in world space, so {how}; the "
            "displaced vertices are the same.")
