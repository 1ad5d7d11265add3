"""Shared bits of Prism's Properties-editor panels."""

from __future__ import annotations

ENGINE_ID = "PRISM"


class PrismPanel:
    """Mixin: a Properties-editor panel shown only while Prism is the render engine."""

    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context):
        return context.engine == ENGINE_ID


class ToggledScenePanel(PrismPanel):
    """Mixin: a panel whose header holds the scene setting ``toggle``; its body lists ``settings``
    (scene settings), greyed out while the toggle is off, then ``draw_more``."""

    toggle = ""
    settings: tuple[str, ...] = ()

    def draw_header(self, context):
        self.layout.prop(context.scene.prism, self.toggle, text="")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        prism = context.scene.prism
        column = layout.column()
        column.active = getattr(prism, self.toggle)
        for name in self.settings:
            column.prop(prism, name)
        self.draw_more(column)

    def draw_more(self, column) -> None:
        """What the panel shows below its settings (nothing by default)."""


def error_label(layout, message: str) -> None:
    """A red label with an error icon (never a traceback)."""
    row = layout.row()
    row.alert = True
    row.label(text=message, icon="ERROR")
