# A nimbus VDB (or name.%04d.vdb sequence) as Blender Volume data, at nimbus's world position (Z up, metres).
import bpy

from . import cache


def point_volume(vol, paths, first_frame=None):
    """Points Volume data `vol` at one file, or at a sequence whose file i is scene frame first_frame + i."""
    vol.filepath = cache.blend_path(paths[0])
    if first_frame is None:
        vol.is_sequence = False
    else:
        # Blender reads frame (scene frame - frame_start + 1) + frame_offset of the sequence: with
        # frame_start = first and frame_offset = first - 1, scene frame n reads name.<n>.vdb.
        vol.is_sequence = True
        vol.frame_start = first_frame
        vol.frame_duration = len(paths)
        vol.frame_offset = first_frame - 1
        vol.sequence_mode = "EXTEND"  # before the first and after the last frame: hold them
    # The grids are read as nimbus wrote them: no clipping of thin voxels, full precision.
    vol.render.clipping = 0.0
    vol.render.precision = "FULL"
    vol.render.space = "OBJECT"
    vol.render.step_size = 0.0  # automatic: the voxel size (times the scene's step rate)
    vol.grids.unload()          # a regenerated file of the same name is read again
    vol.update_tag()


def new_volume(name, paths, first_frame=None):
    vol = bpy.data.volumes.new(name)
    point_volume(vol, paths, first_frame)
    return vol


def new_object(context, name, vol):
    """A new object holding vol at the world origin, scale 1, linked to the active collection."""
    obj = bpy.data.objects.new(name, vol)
    obj.location = (0.0, 0.0, 0.0)
    obj.rotation_euler = (0.0, 0.0, 0.0)
    obj.scale = (1.0, 1.0, 1.0)
    context.collection.objects.link(obj)
    for other in context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj
    return obj

