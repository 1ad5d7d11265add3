"""Walking a Blender shader node tree as Cycles reads it: the Material Output for Cycles, links through
reroutes, muted nodes and node groups (entered and left through their Group Input/Output nodes).

A ``Source`` is an output socket of a real node (never a reroute, group or group socket) in its group
context: the stack of Group nodes it sits inside, so one group used twice compiles twice.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...properties.node_links import valid_link

STRUCTURAL = {"NodeReroute", "NodeGroupInput", "NodeGroupOutput", "ShaderNodeGroup", "NodeFrame"}


@dataclass(frozen=True)
class Source:
    node: object
    identifier: str
    context: tuple = ()

    @property
    def key(self):
        return (self.node.as_pointer(), self.identifier, tuple(g.as_pointer() for g in self.context))


def output_node(tree):
    """The Material Output Cycles renders (target Cycles or All, the active one first), or None."""
    node = tree.get_output_node("CYCLES")
    if node is not None:
        return node
    outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial" and n.target in ("ALL", "CYCLES")]
    return outputs[0] if outputs else None


def _group_output(tree):
    nodes = [n for n in tree.nodes if n.bl_idname == "NodeGroupOutput"]
    active = [n for n in nodes if n.is_active_output]
    return (active or nodes or [None])[0]


def _input(node, identifier):
    return next((s for s in node.inputs if s.identifier == identifier), None)


def follow(socket, context=()):
    """(``Source`` feeding input ``socket`` in group ``context`` or None, the socket whose own value counts
    when nothing does): follows reroutes, muted nodes (their first input of the output's type passes
    through, as in Blender), groups and group inputs (a group input left unlinked outside takes the
    value set on the Group node)."""
    value_socket = socket
    for _ in range(10000):  # bounded: a loop of links Blender has not marked invalid yet ends here
        link = valid_link(socket)
        if link is None:
            return None, value_socket
        node, out = link.from_node, link.from_socket
        if node.bl_idname == "NodeReroute":
            socket = node.inputs[0]
            continue
        if node.mute and node.bl_idname not in STRUCTURAL:
            passed = next((li.from_socket for li in node.internal_links if li.to_socket == out), None)
            if passed is None:
                return None, value_socket
            socket = passed
            if hasattr(socket, "default_value"):
                value_socket = socket
            continue
        if node.bl_idname == "ShaderNodeGroup":
            inner = _group_output(node.node_tree) if node.node_tree is not None else None
            target = _input(inner, out.identifier) if inner is not None else None
            if target is None:
                return None, value_socket
            socket, context = target, context + (node,)
            if hasattr(socket, "default_value"):
                value_socket = socket
            continue
        if node.bl_idname == "NodeGroupInput":
            outer = _input(context[-1], out.identifier) if context else None
            if outer is None:
                return None, value_socket
            socket, context = outer, context[:-1]
            if hasattr(socket, "default_value"):
                value_socket = socket
            continue
        return Source(node, out.identifier, context), value_socket
    return None, value_socket
