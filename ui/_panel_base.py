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


def error_label(layout, message: str) -> None:
    """A red label with an error icon (never a traceback)."""
    row = layout.row()
    row.alert = True
    row.label(text=message, icon="ERROR")
