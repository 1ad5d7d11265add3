"""Links of a Blender node tree as Cycles reads them: a link Blender marks invalid (one link of every loop,
a link between sockets that cannot connect) or that is muted carries nothing, and a chain of reroutes is
followed to the node behind it, a loop of reroutes to nothing.

Every place that follows links (the material panel, the world and AOV export, the node compiler) asks
here, so a loop can hang none of them. No bpy import: the sockets come in as arguments.
"""

from __future__ import annotations

REROUTE = "NodeReroute"


def valid_link(socket):
    """The link that feeds input ``socket`` (valid and not muted), or None."""
    return next((link for link in socket.links if link.is_valid and not link.is_muted), None)


def is_linked(socket) -> bool:
    """Whether something really feeds input ``socket`` (``socket.is_linked`` is also true for an invalid or
    muted link, which Cycles ignores)."""
    return valid_link(socket) is not None


def upstream(socket):
    """(node, output socket) feeding input ``socket`` through reroutes, or (None, None) when nothing does:
    unlinked, an unlinked reroute, or a loop of reroutes (each reroute is passed once)."""
    seen = set()
    link = valid_link(socket)
    while link is not None:
        node, output = link.from_node, link.from_socket
        if node.bl_idname != REROUTE:
            return node, output
        if node.as_pointer() in seen:
            return None, None
        seen.add(node.as_pointer())
        link = valid_link(node.inputs[0])
    return None, None


def upstream_node(socket):
    """The node feeding input ``socket`` through reroutes, or None."""
    return upstream(socket)[0]


def invalid_links(tree) -> list:
    """The links of ``tree`` Blender marks invalid (drawn red in the editor)."""
    return [link for link in tree.links if not link.is_valid] if tree is not None else []
