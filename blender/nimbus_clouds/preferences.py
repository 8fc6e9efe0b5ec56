# Add-on preferences: which backend, the nimbus program's path, the dense-size memory limit.
from types import SimpleNamespace

import bpy

from . import backend, checks

ADDON = __package__


class NimbusPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    backend: bpy.props.EnumProperty(
        name="Backend",
        items=[("AUTO", "Automatic", "The nimbus Python module when it imports, else the nimbus program"),
               ("MODULE", "Module", "The nimbus Python module only"),
               ("PROGRAM", "Program", "The nimbus program only (subprocess)")],
        default="AUTO")
    program: bpy.props.StringProperty(
        name="nimbus program", subtype="FILE_PATH",
        description="Path of the nimbus program (empty: `nimbus` on PATH; the NIMBUS_PROGRAM environment "
                    "variable overrides this)")
    memory_limit_gib: bpy.props.FloatProperty(
        name="Memory limit (GiB)", min=0.001, soft_max=1024.0, default=checks.default_memory_limit_gib(),
        description="Refuse clouds whose box as dense floats exceeds this (default: a quarter of the RAM)")

    def draw(self, context):
        col = self.layout.column()
        col.prop(self, "backend")
        col.prop(self, "program")
        col.prop(self, "memory_limit_gib")
        try:
            col.label(text="Using the " + get_backend(context).describe())
        except Exception as e:  # noqa: shown, never raised in a draw
            col.label(text=str(e), icon="ERROR")


def get(context):
    """The add-on's preferences, or their defaults when it is not registered as an add-on."""
    addon = context.preferences.addons.get(ADDON)
    if addon is not None and addon.preferences is not None:
        return addon.preferences
    return SimpleNamespace(backend="AUTO", program="", memory_limit_gib=checks.default_memory_limit_gib())


def get_backend(context):
    prefs = get(context)
    return backend.choose(prefs.backend, bpy.path.abspath(prefs.program) if prefs.program else "")
