"""Point clouds made the way artists make them: loose vertices turned into points by Geometry Nodes."""

from __future__ import annotations

import bpy


def points_object(name, positions, mat=None, radius=0.3, random_radius=None, location=(0.0, 0.0, 0.0)):
    """A mesh of loose vertices turned into a point cloud by Geometry Nodes (Mesh to Points of ``radius``,
    or per point a Random Value in ``random_radius`` (min, max)), with Set Material ``mat``."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(positions, [], [])
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    tree = bpy.data.node_groups.new(name, "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = tree.nodes, tree.links
    given, out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    to_points = nodes.new("GeometryNodeMeshToPoints")
    to_points.inputs["Radius"].default_value = radius
    links.new(given.outputs[0], to_points.inputs["Mesh"])
    last = to_points.outputs[0]
    if random_radius is not None:
        random = nodes.new("FunctionNodeRandomValue")
        random.data_type = "FLOAT"
        random.inputs[2].default_value, random.inputs[3].default_value = random_radius  # Min, Max (float)
        links.new(random.outputs[1], to_points.inputs["Radius"])
    if mat is not None:
        set_material = nodes.new("GeometryNodeSetMaterial")
        set_material.inputs["Material"].default_value = mat
        links.new(last, set_material.inputs["Geometry"])
        last = set_material.outputs[0]
    links.new(last, out.inputs[0])
    obj.modifiers.new("Points", "NODES").node_group = tree
    return obj
