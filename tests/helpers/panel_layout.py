"""Drawing Prism's panels headless, checked against Blender's own RNA.

Headless Blender has no Properties editor to draw into, so ``draw`` runs with a
recording layout that checks every call against Blender's own RNA: the method and
its keyword arguments must exist on ``UILayout``, every ``prop(data, name)`` must
name a property of ``data``, icons must be real icon names. A misspelt property
fails the test just as it would print an error in Blender.
"""

from __future__ import annotations

from types import SimpleNamespace


class RecordingLayout:
    """Stands in for ``bpy.types.UILayout``: validates and records each call."""

    def __init__(self, log):
        object.__setattr__(self, "_log", log)

    def __setattr__(self, name, value):
        import bpy

        assert name in bpy.types.UILayout.bl_rna.properties, f"UILayout has no attribute '{name}'"

    def __getattr__(self, name):
        import bpy

        function = bpy.types.UILayout.bl_rna.functions.get(name)
        assert function is not None, f"UILayout has no method '{name}'"
        parameters = function.parameters

        def call(*args, **kwargs):
            for key in kwargs:
                assert key in parameters, f"UILayout.{name}() has no argument '{key}'"
            icon = kwargs.get("icon")
            if icon is not None:
                assert icon in parameters["icon"].enum_items, f"unknown icon '{icon}'"
            self._check(name, args, kwargs)
            self._log.append((name, args, kwargs))
            if name == "operator":
                return SimpleNamespace()
            return RecordingLayout(self._log)

        return call

    @staticmethod
    def _check(name, args, kwargs):
        pairs = []
        if name in {"prop", "prop_decorator", "template_ID"}:
            pairs.append((args[0] if args else kwargs["data"], args[1] if len(args) > 1 else kwargs["property"]))
        elif name == "prop_search":
            pairs += [(args[0], args[1]), (args[2], args[3])]
        for data, prop in pairs:
            assert data is not None, f"{name}() was given None for '{prop}'"
            assert prop in data.bl_rna.properties, f"{data.bl_rna.identifier} has no property '{prop}'"


class _PanelStandIn(SimpleNamespace):
    """``self`` for a panel's draw(): a recording layout, and the panel class's attributes and methods
    (Blender panels cannot be instantiated outside a redraw)."""

    def __getattr__(self, name):
        value = getattr(self.panel_class, name)
        return value.__get__(self) if callable(value) and hasattr(value, "__get__") else value


def draw(panel_class, context):
    log = []
    panel = _PanelStandIn(layout=RecordingLayout(log), bl_space_type="PROPERTIES", panel_class=panel_class)
    panel_class.draw(panel, context)
    return log


def context(scene, engine="PRISM", camera=None, light=None, material=None, obj=None, world=None):
    return SimpleNamespace(engine=engine, scene=scene, camera=camera, light=light, material=material, object=obj,
                           world=world, view_layer=scene.view_layers[0])


def labels(log):
    return [kwargs.get("text", "") for name, _, kwargs in log if name == "label"]


def props(log):
    return [args[1] for name, args, _ in log if name == "prop"]
