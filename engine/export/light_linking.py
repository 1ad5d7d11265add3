"""Blender's Light Linking and Shadow Linking → ``tracer.light_linking.LightLinks`` (receiver and blocker
sets per object, membership masks per emitter).

An emitter (a light, or a mesh object with an emissive material) names a collection in
``Object.light_linking.receiver_collection`` (which objects it lights) and ``blocker_collection`` (which
objects cast its shadows). Each object or child collection in it is included or excluded
(``CollectionLightLinking.link_state``). As Blender's manual says: only included objects given, the
emitter affects only those; only excluded, every object but those; both, the included minus the excluded.
A child collection's state applies to every object in it (``Collection.all_objects``).

Sets as Cycles builds them (one set per distinct combination of emitters that affect an object, set 0 for
the objects no collection singles out, at most 64: Cycles' ``LIGHT_LINK_SET_MAX``); the kernel side is
``tracer/light_linking.py``.
"""

from __future__ import annotations

import numpy as np

from ..tracer.light_linking import ALL_SETS, MAX_SETS, LightLinks


class _Rule:
    """Which objects one emitter's collection admits (lights, or lets cast shadows)."""

    def __init__(self, collection):
        self.included: set[str] = set()
        self.excluded: set[str] = set()
        # ``collection_children`` / ``collection_objects`` hold only the states, in the order of ``children``
        # / ``objects`` (the same lists in Blender's data)
        for child, entry in zip(collection.children, collection.collection_children):
            into = self.included if entry.light_linking.link_state == "INCLUDE" else self.excluded
            into.update(obj.name for obj in child.all_objects)
        for obj, entry in zip(collection.objects, collection.collection_objects):
            into = self.included if entry.light_linking.link_state == "INCLUDE" else self.excluded
            into.add(obj.name)
        self.only_included = bool(self.included)

    def admits(self, name: str | None) -> bool:
        """``name`` None: an object in no collection."""
        if name in self.excluded:
            return False
        return name in self.included if self.only_included else True


def _signed(mask: int) -> int:
    """A 64-bit mask as the int64 the kernels read."""
    return mask - (1 << 64) if mask >= 1 << 63 else mask


def _sets(rules: list, names: list[str], what: str, warnings: list[str]) -> tuple[np.ndarray, list[int]]:
    """(set of each object [objects] int64, mask of each rule's emitter): objects the same emitters admit
    share a set; set 0 holds those admitted as an object in no collection is."""
    index = {tuple(rule.admits(None) for _, rule in rules): 0}
    object_set = np.zeros(len(names), np.int64)
    overflow = []
    for o, name in enumerate(names):
        signature = tuple(rule.admits(name) for _, rule in rules)
        if signature not in index:
            if len(index) >= MAX_SETS:
                overflow.append(name)
                continue
            index[signature] = len(index)
        object_set[o] = index[signature]
    if overflow:
        warnings.append(f"{what}: more than {MAX_SETS} different sets of objects (Cycles' limit too); "
                        f"{', '.join(repr(n) for n in overflow[:5])}{' …' if len(overflow) > 5 else ''} are "
                        "rendered as objects no linking names (lit and shadowed by every emitter).")
    masks = []
    for e in range(len(rules)):
        mask = 0
        for signature, s in index.items():
            if signature[e]:
                mask |= 1 << s
        masks.append(_signed(mask))
    return object_set, masks


def _emitters(depsgraph, object_names: list[str]) -> tuple[dict, dict]:
    """(light name → its original object, mesh object name → its original object) of the emitters with a
    receiver or blocker collection; meshes only where they are rendered (``object_names``)."""
    rendered = set(object_names)
    lights, meshes = {}, {}
    for instance in depsgraph.object_instances:
        obj = instance.object
        linking = getattr(obj.original, "light_linking", None)
        if linking is None or (linking.receiver_collection is None and linking.blocker_collection is None):
            continue
        if obj.type == "LIGHT":
            lights.setdefault(obj.name, obj.original)
        elif obj.name in rendered:
            meshes.setdefault(obj.name, obj.original)
    return lights, meshes


def export_light_links(depsgraph, object_names: list[str], warnings: list[str] | None = None) -> LightLinks | None:
    """The scene's light and shadow linking for the objects ``object_names`` (``Scene.object_names``), or
    None when no emitter has a receiver or blocker collection."""
    lights, meshes = _emitters(depsgraph, object_names)
    if not (lights or meshes):
        return None
    warnings = warnings if warnings is not None else []
    emitters = [("light", name, obj) for name, obj in lights.items()] + [("mesh", name, obj) for name, obj in meshes.items()]
    n = len(object_names)
    result = {}
    for kind, attribute in (("light", "receiver_collection"), ("shadow", "blocker_collection")):
        rules = [(e, _Rule(getattr(e[2].light_linking, attribute))) for e in emitters
                 if getattr(e[2].light_linking, attribute) is not None]
        what = "Light Linking" if kind == "light" else "Shadow Linking"
        object_set, masks = _sets(rules, object_names, what, warnings) if rules else (np.zeros(n, np.int64), [])
        by_light, by_object = {}, np.full(n, ALL_SETS, np.int64)
        names = np.array(object_names, dtype=object)
        for ((emitter_kind, name, _), _), mask in zip(rules, masks):
            if emitter_kind == "light":
                by_light[name] = mask
            else:
                by_object[names == name] = mask
        result[kind] = (object_set, by_object, by_light)
    return LightLinks(object_receiver_set=result["light"][0], object_blocker_set=result["shadow"][0],
                      object_light_sets=result["light"][1], object_shadow_sets=result["shadow"][1],
                      light_sets=result["light"][2], light_shadow_sets=result["shadow"][2])


def viewport_linking_warnings(depsgraph) -> list[str]:
    """The rendered viewport does not apply linking (F12 does): one warning per linked emitter."""
    warned = []
    for instance in depsgraph.object_instances:
        obj = instance.object
        linking = getattr(obj.original, "light_linking", None)
        if linking is None or (linking.receiver_collection is None and linking.blocker_collection is None):
            continue
        if obj.name not in warned:
            warned.append(obj.name)
    return [f"Object '{name}': the rendered viewport ignores its Light Linking and Shadow Linking (the emitter "
            "lights every object and every object casts its shadows); F12 renders them as Cycles does."
            for name in warned]
