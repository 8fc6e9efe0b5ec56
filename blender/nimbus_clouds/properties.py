# The cloud's settings (on the object, and on the Add operator): preset, seed, voxel size, time, look, frames.
import bpy

from . import preferences

DEFAULT_PRESET = "cumulus-humilis"
_items = []   # the preset enum's items, kept alive while Blender shows them (a dynamic enum's rule)
_names = []


def preset_names(context=None):
    """The backend's preset names, DEFAULT_PRESET first (cached once read); [] when no backend answers."""
    global _names
    if not _names:
        try:
            names = list(preferences.get_backend(context or bpy.context).presets())
        except Exception:  # noqa: no backend yet; the panel says why
            return []
        _names = sorted(names, key=lambda n: n != DEFAULT_PRESET)  # stable: the rest keep nimbus's order
    return _names


def forget_presets():
    global _names
    _names = []


def _preset_items(self, context):
    global _items
    names = preset_names(context)
    if not names:
        _items = [("NONE", "(nimbus not found)", "Neither the nimbus module nor the program answered", 0)]
    else:
        _items = [(n, n, f"nimbus preset {n}", i) for i, n in enumerate(names)]
    return _items


def _get_preset(self):
    names = preset_names()
    return names.index(self.preset_name) if self.preset_name in names else 0


def _set_preset(self, value):
    names = preset_names()
    if 0 <= value < len(names):
        self.preset_name = names[value]
        look_from_preset(self, bpy.context)


def look_from_preset(props, context):
    """coverage and density back to the preset's own values."""
    try:
        cloud = preferences.get_backend(context).preset(preset_of(props)).get("cloud", {})
    except Exception:  # noqa: an unknown preset is refused when generating
        return
    if "coverage" in cloud:
        props.coverage = float(cloud["coverage"])
    if "density" in cloud:
        props.density = float(cloud["density"])


def place(obj):
    """The object at the world origin, or half a voxel towards -x-y-z with cycles_shift (docs/blender.md)."""
    s = obj.nimbus
    obj.location = (-0.5 * s.voxel_size_used,) * 3 if s.cycles_shift else (0.0, 0.0, 0.0)


def _update_shift(self, context):
    if isinstance(self.id_data, bpy.types.Object):
        place(self.id_data)


def preset_of(props):
    """The preset's name: the object's settings keep it as text (preset_name), the operator as its enum."""
    name = getattr(props, "preset_name", None)
    return name if name is not None else props.preset


def _look_update(self, context):
    look_from_preset(self, context)


def cloud_properties(operator=False):
    """The properties shared by the object's settings and (operator=True) the Add operator.

    The object keeps the preset's name as text behind its enum (a dynamic enum stores an index, which a
    changed preset list would move); the operator, whose values do not outlive it, keeps the enum alone
    (an enum setter that writes other properties leaks memory when Python passes it as a keyword)."""
    P = bpy.props
    if operator:
        preset = {"preset": P.EnumProperty(name="Preset", items=_preset_items, update=_look_update,
                                           description="nimbus preset (nimbus presets)")}
    else:
        preset = {"preset_name": P.StringProperty(name="Preset name", default=DEFAULT_PRESET),
                  "preset": P.EnumProperty(name="Preset", items=_preset_items, get=_get_preset, set=_set_preset,
                                           description="nimbus preset (nimbus presets)")}
    return {
        **preset,
        "use_preset_seed": P.BoolProperty(name="Preset's seed", default=True,
                                          description="Use the preset's own seed"),
        "seed": P.IntProperty(name="Seed", default=1, soft_min=0,
                              description="Random seed, 0 to 4294967295 (the same seed gives the same cloud)"),
        "voxel_size": P.FloatProperty(name="Voxel size", default=0.0, soft_min=0.0, soft_max=1000.0, unit="LENGTH",
                                      precision=3,
                                      description="Voxel size in metres (0: the preset's, times the size factor)"),
        "time": P.FloatProperty(name="Time (s)", default=0.0, soft_min=0.0,
                                description="Time in seconds: wind and evolution (animated: the first frame's time, "
                                            "to whole frames)"),
        "coverage": P.FloatProperty(name="Coverage", default=0.68, soft_min=0.0, soft_max=1.0,
                                    description="How much of the preset's shapes holds cloud (0..1)"),
        "density": P.FloatProperty(name="Density", default=1.0, soft_min=0.0, soft_max=5.0,
                                   description="Density multiplier"),
        "size": P.FloatProperty(name="Size factor", default=1.0, soft_min=0.1, soft_max=10.0,
                                description="Scales the shapes about the cloud's base centre and the noise with them"),
        "animated": P.BoolProperty(name="Animated", default=False,
                                   description="Generate a VDB sequence for the frame range (wind and evolution)"),
        "frame_first": P.IntProperty(name="First frame", default=1),
        "frame_last": P.IntProperty(name="Last frame", default=24),
        "cycles_shift": P.BoolProperty(
            name="Cycles half-voxel shift", default=True, update=_update_shift,
            description="Move the object half a voxel towards -x-y-z: Cycles 3.x (NanoVDB) draws a grid's voxels "
                        "half a voxel towards +x+y+z of where OpenVDB, EEVEE and nimbus put them"),
    }


class NimbusCloudSettings(bpy.types.PropertyGroup):
    """A nimbus cloud's settings, on its object (Object.nimbus)."""
    is_cloud: bpy.props.BoolProperty(name="nimbus cloud", default=False)
    backend_used: bpy.props.StringProperty(name="Backend used")
    voxel_size_used: bpy.props.FloatProperty(name="Voxel size used", unit="LENGTH",
                                             description="The voxel size of the files (metres)")


NimbusCloudSettings.__annotations__.update(cloud_properties())
