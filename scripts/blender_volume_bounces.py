# How much of a nimbus cloud's light Cycles gets at each volume-bounce count: the add-on's cloud
# (cumulus-humilis at 12 m voxels) lit by a sun from the front and above, clouds alone over black,
# its mean luminance over covered pixels (alpha > 0.2) against 256 bounces. The figures behind the
# add-on's 32 bounces (blender/nimbus_clouds/render_settings.py, docs/blender.md).
#
#   blender -b --factory-startup --python scripts/blender_volume_bounces.py -- [--nimbus-python build/python]
import argparse
import os
import sys
import tempfile
import time

import addon_utils
import bpy
import numpy as np
from mathutils import Vector

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BOUNCES = (0, 4, 16, 32, 64, 256)


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_volume_bounces.py")
    p.add_argument("--nimbus-python", default="", help="folder holding the nimbus module (optional)")
    p.add_argument("--spp", type=int, default=64)
    return p.parse_args(argv)


def set_up_scene():
    scene = bpy.context.scene
    bpy.data.objects.remove(bpy.data.objects["Cube"])
    assert bpy.ops.nimbus.add_cloud(preset="cumulus-humilis", voxel_size=12.0) == {"FINISHED"}
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    scene.collection.objects.link(sun)
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_mode = "QUATERNION"
    sun.rotation_quaternion = Vector((0.4, -0.6, 0.7)).normalized().to_track_quat("Z", "Y")
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    scene.camera = cam
    cam.location = Vector((0, -3000, 1300))  # the humilis spans x +-528, y +-456, z 900..1236 m
    cam.data.clip_end, cam.data.lens = 1e5, 35
    cam.rotation_mode = "QUATERNION"
    cam.rotation_quaternion = (Vector((0, 0, 1068)) - cam.location).to_track_quat("-Z", "Y")
    return scene


def mean_cloud_luminance(path):
    img = bpy.data.images.load(path)
    px = np.empty(img.size[0] * img.size[1] * 4, np.float32)
    img.pixels.foreach_get(px)
    px = px.reshape(-1, 4)
    covered = px[:, 3] > 0.2
    lum = 0.2126 * px[:, 0] + 0.7152 * px[:, 1] + 0.0722 * px[:, 2]
    return float(lum[covered].mean()), int(covered.sum())


def main():
    a = parse()
    sys.path.insert(0, os.path.join(REPO, "blender"))
    if a.nimbus_python:
        sys.path.insert(0, os.path.abspath(a.nimbus_python))
    addon_utils.enable("nimbus_clouds", default_set=True)
    scene = set_up_scene()
    c = scene.cycles
    scene.render.engine = "CYCLES"
    c.device, c.samples, c.use_adaptive_sampling, c.use_denoising = "CPU", a.spp, False, False
    c.transparent_max_bounces = 64
    r = scene.render
    r.film_transparent = True
    r.resolution_x, r.resolution_y, r.resolution_percentage = 64, 48, 100
    r.image_settings.file_format, r.image_settings.color_mode = "OPEN_EXR", "RGBA"
    out = tempfile.mkdtemp(prefix="nimbus-bounces-")
    means = {}
    for b in BOUNCES:
        c.max_bounces, c.volume_bounces = max(b, 12), b
        r.filepath = os.path.join(out, f"bounces-{b}.exr")
        t = time.time()
        bpy.ops.render.render(write_still=True)
        means[b] = (*mean_cloud_luminance(r.filepath), time.time() - t)
    print(f"\ncumulus-humilis, 64x48, {a.spp} spp, Blender {bpy.app.version_string}\n")
    print("| volume bounces | mean cloud luminance | of 256 bounces | covered pixels | render s |")
    print("|---:|---:|---:|---:|---:|")
    for b, (m, n, s) in means.items():
        print(f"| {b} | {m:.4f} | {100 * m / means[256][0]:.1f} % | {n} | {s:.1f} |")


main()
