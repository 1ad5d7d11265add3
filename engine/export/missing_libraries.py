"""Linked libraries Blender could not open when it loaded the file: what they would have put in the
scene is missing (Blender keeps empty placeholders), so each missing library is named, with its
file and the objects it leaves out, never a silent gap or a vague "no visible geometry"."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class MissingLibrary:
    name: str
    path: str  # the file Blender looked for (absolute)
    objects: list[str] = field(default_factory=list)  # the scene's objects whose data it should hold

    def sentence(self) -> str:
        """What is missing and the fix, as a clause (no capital, no full stop)."""
        shown = ", ".join(f"'{name}'" for name in self.objects[:5])
        more = f" and {len(self.objects) - 5} more" if len(self.objects) > 5 else ""
        several = len(self.objects) > 1
        return (f"the linked library '{self.name}' is missing (no file at {self.path}), so "
                f"{'objects' if several else 'object'} {shown}{more} from it {'are' if several else 'is'} not "
                "rendered: relocate it (Outliner ▸ Blender File ▸ right-click the library ▸ Relocate) or restore "
                "the file")


def _missing_library(data_block):
    """The library of ``data_block`` when it is a placeholder of a missing library's data, else None."""
    if data_block is None or not getattr(data_block, "is_missing", False):
        return None
    library = data_block.library
    return library if library is not None and library.is_missing else None


def missing_libraries(scene) -> list[MissingLibrary]:
    """The missing libraries that ``scene``'s objects (their object, data or instanced collection) link from."""
    import bpy

    found: dict[str, MissingLibrary] = {}
    for obj in scene.objects:
        for data_block in (obj, obj.data, obj.instance_collection):
            library = _missing_library(data_block)
            if library is None:
                continue
            entry = found.get(library.name)
            if entry is None:
                path = bpy.path.abspath(library.filepath, library=library.parent)
                entry = found[library.name] = MissingLibrary(library.name, path)
            if obj.name not in entry.objects:
                entry.objects.append(obj.name)
            break
    return list(found.values())
