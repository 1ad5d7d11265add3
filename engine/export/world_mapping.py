"""The vector a world texture is looked up with → one 3x3 matrix from world directions.

A world texture's Vector input is the view direction unless it is linked; Prism follows a chain of
Mapping nodes (any type: rotation and scale; the location of a Point or Texture mapping only shifts the
direction, which Prism cannot represent, so it is reported) back to a Texture Coordinate node's
Generated or Object output (Object with an object: that object's rotation). Anything else is reported
and the plain direction is used.
"""

from __future__ import annotations

import numpy as np

from ..properties.node_links import is_linked, upstream


def linked_source(socket):
    """(node, output socket) feeding ``socket`` through reroutes, or (None, None) (invalid links and reroute
    loops feed nothing: ``node_links``)."""
    return upstream(socket)


def _euler_matrix(angles) -> np.ndarray:
    from mathutils import Euler

    return np.array(Euler(tuple(float(a) for a in angles), "XYZ").to_matrix(), dtype=np.float64)


def _mapping_matrix(node, where: str, warnings) -> np.ndarray:
    for name in ("Location", "Rotation", "Scale"):
        socket = node.inputs.get(name)
        if socket is not None and is_linked(socket) and warnings is not None:
            warnings.append(f"{where}: the link into Mapping '{node.name}' {name} is ignored; its own value is used.")
    rotation = _euler_matrix(node.inputs["Rotation"].default_value)
    scale = np.array(node.inputs["Scale"].default_value, dtype=np.float64)
    kind = node.vector_type
    location = np.array(node.inputs["Location"].default_value, dtype=np.float64) if "Location" in node.inputs else 0
    if kind in ("POINT", "TEXTURE") and np.any(location != 0) and warnings is not None:
        warnings.append(f"{where}: Mapping '{node.name}' Location is ignored: a world texture is looked up by "
                        "direction, which a location cannot move.")
    if kind == "TEXTURE":
        with np.errstate(divide="ignore"):
            return np.diag(1.0 / scale) @ rotation.T
    if kind == "NORMAL":
        with np.errstate(divide="ignore"):
            return rotation @ np.diag(1.0 / scale)
    return rotation @ np.diag(scale)


def texture_matrix(vector_socket, where: str, warnings) -> np.ndarray:
    """World direction → lookup direction of a world texture whose Vector input is ``vector_socket``
    (``where`` names the world and node in messages)."""
    matrix = np.eye(3)
    node, output = linked_source(vector_socket)
    while node is not None:
        if node.bl_idname == "ShaderNodeMapping":
            matrix = matrix @ _mapping_matrix(node, where, warnings)
            node, output = linked_source(node.inputs["Vector"])
            continue
        if node.bl_idname == "ShaderNodeTexCoord" and output.name in ("Generated", "Object"):
            target = node.object if output.name == "Object" else None
            if target is not None:
                rotation = np.array(target.matrix_world.to_3x3().normalized(), dtype=np.float64)
                matrix = matrix @ rotation.T
            return matrix
        if warnings is not None:
            warnings.append(f"{where}: the vector from '{node.name}' is not supported; Prism looks the texture up "
                            "by direction (Texture Coordinate Generated through Mapping nodes).")
        return matrix
    return matrix
