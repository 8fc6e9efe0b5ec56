# The View3D sidebar's "nimbus" tab for the active nimbus cloud, and the Add > Volume menu entry.
import bpy

from . import cache, material, operators, preferences, properties


class VIEW3D_PT_nimbus_cloud(bpy.types.Panel):
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "nimbus"
    bl_label = "nimbus Cloud"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is None or obj.type != "VOLUME" or not obj.nimbus.is_cloud:
            layout.label(text="Add one: Add > Volume > nimbus Cloud")
            draw_backend(context, layout)
            return
        s = obj.nimbus
        if properties.preset_names(context) and s.preset_name not in properties.preset_names(context):
            layout.label(text=f"Preset '{s.preset_name}' is not in nimbus's list", icon="ERROR")
        operators.draw_settings(layout, s)
        if s.animated:
            layout.label(text=f"fps {operators.scene_fps(context.scene):g} (the scene's)")
        layout.operator(operators.NIMBUS_OT_regenerate.bl_idname, icon="FILE_REFRESH")

        mat = obj.data.materials[0] if obj.data.materials else None
        box = layout.box()
        box.label(text="Optics (material)")
        for name, text in ((material.N_EXTINCTION, "Extinction per density (1/m)"),
                           (material.N_ALBEDO, "Albedo"), (material.N_WEIGHT, "Forward lobe weight")):
            node = material.value_node(mat, name)
            if node is not None:
                box.prop(node.outputs[0], "default_value", text=text)
        if material.value_node(mat, material.N_EXTINCTION) is None:
            box.label(text="Not the add-on's material", icon="INFO")
        draw_backend(context, layout, s.backend_used)


def draw_backend(context, layout, used=""):
    """The cache folder, the backend and Reload Presets."""
    col = layout.column(align=True)
    col.label(text="Cache: " + cache.cache_folder())
    try:
        col.label(text="Backend: " + (used or preferences.get_backend(context).describe()))
    except Exception as e:  # noqa: shown, never raised in a draw
        col.label(text=str(e), icon="ERROR")
    col.operator(operators.NIMBUS_OT_reload_presets.bl_idname, icon="FILE_REFRESH")


def menu_entry(self, context):
    self.layout.operator(operators.NIMBUS_OT_add_cloud.bl_idname, text="nimbus Cloud", icon="OUTLINER_OB_VOLUME")
