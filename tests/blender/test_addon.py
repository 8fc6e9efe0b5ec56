# Headless Blender test of the nimbus_clouds add-on: add, place, material, sequence, render, refusals (both backends).
#
#   blender -b --factory-startup --python tests/blender/test_addon.py -- \
#       --nimbus-python BUILD/python --nimbus-program BUILD/nimbus --repo REPO
#
# Exits 1 (printing every failed check) on any failure; 0 when all checks pass.
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import traceback

import bpy
import numpy as np
from mathutils import Vector

FAILED = []
VOXEL = 24.0  # metres: cumulus-humilis at 24 m is about 34 x 30 x 12 voxels, generated in well under a second


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        FAILED.append(what)
    return ok


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="test_addon.py")
    p.add_argument("--nimbus-python", default="")
    p.add_argument("--nimbus-program", required=True)
    p.add_argument("--repo", required=True)
    return p.parse_args(argv)


def nimbus_info(program, path):
    """World bbox (voxel corners), voxel size and time of a VDB, from `nimbus info`."""
    out = subprocess.run([program, "info", path], capture_output=True, text=True, timeout=60).stdout
    nums = r"\(([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+)\)"
    box = re.search(r"world bbox:\s+" + nums + " to " + nums, out)
    index = re.search(r"index bbox:\s+" + nums + " to " + nums, out)
    vs = re.search(r"voxel size:\s+([0-9.e+-]+)", out)
    t = re.search(r"^\s*time: ([-0-9.e+]+)", out, re.M)
    return {"lo": [float(v) for v in box.groups()[:3]] if box else None,
            "hi": [float(v) for v in box.groups()[3:]] if box else None,
            "index": [int(v) for v in index.groups()] if index else None,
            "voxel": float(vs.group(1)) if vs else None, "time": float(t.group(1)) if t else None}


def mesh_bounds(volume_obj):
    """Bounds of the grid's voxels in the file's own coordinates: Volume to Mesh (threshold 1e-6) of its data.

    OpenVDB's volume-to-mesh (as Blender 3.4 runs it) puts the surface half a voxel towards +x+y+z of
    the voxels (measured: a box of voxel centres c0..c1 meshes to c0 - 0.5..c1 + 1.5 voxels); the
    caller takes that half voxel off."""
    mesh_obj = bpy.data.objects.new("bounds probe", bpy.data.meshes.new("bounds probe"))
    bpy.context.scene.collection.objects.link(mesh_obj)
    tree = bpy.data.node_groups.new("bounds probe", "GeometryNodeTree")
    out = tree.nodes.new("NodeGroupOutput")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    info = tree.nodes.new("GeometryNodeObjectInfo")
    info.transform_space = "ORIGINAL"
    info.inputs["Object"].default_value = volume_obj
    to_mesh = tree.nodes.new("GeometryNodeVolumeToMesh")
    to_mesh.resolution_mode = "GRID"
    to_mesh.inputs["Threshold"].default_value = 1e-6
    tree.links.new(info.outputs["Geometry"], to_mesh.inputs["Volume"])
    tree.links.new(to_mesh.outputs["Mesh"], out.inputs[0])
    mod = mesh_obj.modifiers.new("bounds probe", "NODES")
    mod.node_group = tree
    deps = bpy.context.evaluated_depsgraph_get()
    evaluated = mesh_obj.evaluated_get(deps)
    mesh = evaluated.to_mesh()
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
    mesh.vertices.foreach_get("co", co)
    evaluated.to_mesh_clear()
    bpy.data.objects.remove(mesh_obj)
    bpy.data.node_groups.remove(tree)
    if co.size == 0:
        return None
    co = co.reshape(-1, 3)
    return co.min(axis=0), co.max(axis=0)


class FakeOperator:
    """Stands in for the Add operator so that its execute() can be called directly and its return seen."""

    def __init__(self, **given):
        rna = bpy.ops.nimbus.add_cloud.get_rna_type()
        for prop in rna.properties:
            if prop.identifier != "rna_type" and prop.type != "ENUM":
                setattr(self, prop.identifier, prop.default)
        for k, v in given.items():
            setattr(self, k, v)
        self.reports = []
        given_names = set(given)
        self.properties = type("Props", (), {"is_property_set": staticmethod(lambda name: name in given_names)})()

    def report(self, kind, message):
        self.reports.append((set(kind), message))


class FakeLayout:
    """Records what a panel draws, and whether each property and operator it names exists."""

    def __init__(self, calls):
        self.calls, self.enabled = calls, True

    def prop(self, data, name, **kw):
        self.calls.append(("prop", name, name in data.bl_rna.properties))

    def operator(self, idname, **kw):
        category, name = idname.split(".")
        self.calls.append(("operator", idname, hasattr(getattr(bpy.ops, category), name)))

    def label(self, text="", **kw):
        self.calls.append(("label", text, True))

    def separator(self, **kw):
        pass

    def column(self, **kw):
        return FakeLayout(self.calls)

    row = box = column


def check_panel(obj):
    """The sidebar panel draws the active cloud's settings, its optics, Regenerate and the cache folder."""
    from nimbus_clouds import cache, panel
    calls = []
    fake = type("Panel", (), {"layout": FakeLayout(calls)})()
    bpy.context.view_layer.objects.active = obj
    panel.VIEW3D_PT_nimbus_cloud.draw(fake, bpy.context)
    drawn = {name for kind, name, _ in calls if kind == "prop"}
    missing = [c for c in calls if not c[2]]
    check(not missing, f"panel: every property and operator it draws exists (missing: {missing})")
    check({"preset", "seed", "voxel_size", "time", "coverage", "density", "size", "animated", "frame_first",
           "frame_last", "default_value"} <= drawn, f"panel: draws preset, seed, voxel size, time, coverage, density, "
                                                    f"size, frames and the material's values ({sorted(drawn)})")
    check(("operator", "nimbus.regenerate", True) in calls, "panel: has Regenerate")
    check(any(kind == "label" and name == "Cache: " + cache.cache_folder() for kind, name, _ in calls),
          f"panel: shows the cache folder {cache.cache_folder()}")


def add(**kw):
    return bpy.ops.nimbus.add_cloud(**kw)


def library_optics(program):
    """The look nimbus render gives a cloud by default, as the library states it (--plan-json)."""
    import json
    out = subprocess.run([program, "generate", "--preset", "cumulus-humilis", "--plan-json"], capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out)["optics"]


def check_material(obj, label, program):
    from nimbus_clouds import material as M
    optics = library_optics(program)
    ext, alb, ph = optics["extinction_per_m"], optics["albedo"], optics["phase"]
    check((ext, alb, ph["g_forward"], ph["g_back"], ph["forward_weight"]) == (0.04, 0.99, 0.7, -0.25, 0.8),
          f"{label}: the library's default look is extinction 0.04, albedo 0.99, dual:0.7,-0.25,0.8 ({optics})")
    mat = obj.data.materials[0] if obj.data.materials else None
    if not check(mat is not None and mat.use_nodes, f"{label}: the volume has a node material"):
        return
    n = mat.node_tree.nodes
    value = lambda name: n[name].outputs[0].default_value if name in n else None  # noqa: E731
    check(name_is(n, M.N_DENSITY, "ShaderNodeAttribute") and n[M.N_DENSITY].attribute_name == "density",
          f"{label}: an Attribute node reads the grid 'density'")
    for node, want, what in ((M.N_EXTINCTION, ext, "extinction per unit density"), (M.N_ALBEDO, alb, "albedo"),
                             (M.N_WEIGHT, ph["forward_weight"], "forward lobe weight"),
                             (M.N_G_FORWARD, ph["g_forward"], "forward g"), (M.N_G_BACKWARD, ph["g_back"], "backward g")):
        check(value(node) is not None and abs(value(node) - want) < 1e-7,
              f"{label}: the material's {what} is the library's {want} (got {value(node)})")

    def linked(to_node, socket, from_node):
        s = n[to_node].inputs[socket] if to_node in n else None
        return s is not None and s.is_linked and s.links[0].from_node.name == from_node

    check(linked(M.N_SIGMA_T, 0, M.N_DENSITY) and linked(M.N_SIGMA_T, 1, M.N_EXTINCTION)
          and n[M.N_SIGMA_T].operation == "MULTIPLY", f"{label}: sigma_t = density x extinction")
    check(name_is(n, M.N_SCATTER, "ShaderNodeVolumeScatter") and linked(M.N_SCATTER, "Density", M.N_SIGMA_T)
          and linked(M.N_SCATTER, "Color", M.N_ALBEDO), f"{label}: Volume Scatter of sigma_t with colour albedo")
    check(linked(M.N_SCATTER, "Anisotropy", M.N_G) and linked(M.N_G, 0, M.N_IS_FORWARD)
          and linked(M.N_IS_FORWARD, 0, M.N_NOISE) and linked(M.N_IS_FORWARD, 1, M.N_WEIGHT)
          and n[M.N_IS_FORWARD].operation == "LESS_THAN", f"{label}: anisotropy g_f where noise < weight, else g_b")
    check(name_is(n, M.N_ABSORPTION, "ShaderNodeVolumeAbsorption") and linked(M.N_ABSORPTION, "Density", M.N_SIGMA_T)
          and linked(M.N_ABSORPTION, "Color", M.N_ALBEDO), f"{label}: Volume Absorption (1 - albedo) x sigma_t")
    out = n.get(M.N_OUTPUT)
    check(out is not None and out.inputs["Volume"].is_linked and not out.inputs["Surface"].is_linked,
          f"{label}: the material's output has a volume and no surface")
    # The anisotropy the tree computes for a forward and a backward event.
    g_f, g_b = value(M.N_G_FORWARD), value(M.N_G_BACKWARD)
    check(n[M.N_G].operation == "MULTIPLY_ADD" and linked(M.N_G, 1, M.N_G_SPREAD) and linked(M.N_G, 2, M.N_G_BACKWARD)
          and abs((1 * (g_f - g_b) + g_b) - ph["g_forward"]) < 1e-7, f"{label}: g = forward x (g_f - g_b) + g_b")


def name_is(nodes, name, idname):
    return name in nodes and nodes[name].bl_idname == idname


def check_still(program, label):
    before = len(bpy.data.objects)
    cycles = bpy.context.scene.cycles
    cycles.volume_bounces, cycles.max_bounces, cycles.use_denoising = 0, 12, True  # Cycles' defaults
    t = time.time()
    r = add(preset="cumulus-humilis", voxel_size=VOXEL)
    check(r == {"FINISHED"}, f"{label}: Add nimbus Cloud finishes ({r}, {time.time() - t:.1f} s)")
    check(cycles.volume_bounces >= 32 and cycles.max_bounces >= 32,
          f"{label}: adding a cloud raises Cycles' bounces from 0 (single scattering: grey smoke) to 32 "
          f"({cycles.volume_bounces}, {cycles.max_bounces})")
    check(cycles.use_denoising == bool(cycles.denoiser),
          f"{label}: denoising stays on only where this Blender has a denoiser ({cycles.denoiser!r})")
    obj = bpy.context.active_object
    if not check(obj is not None and obj.type == "VOLUME" and len(bpy.data.objects) == before + 1,
                 f"{label}: one new Volume object, active"):
        return None
    check(obj.nimbus.is_cloud and obj.nimbus.preset_name == "cumulus-humilis", f"{label}: it is marked a nimbus cloud")
    check(obj.nimbus.backend_used.startswith(label), f"{label}: generated by the {label} ({obj.nimbus.backend_used})")
    check(tuple(obj.scale) == (1.0, 1.0, 1.0) and tuple(obj.rotation_euler) == (0.0, 0.0, 0.0),
          f"{label}: scale 1, no rotation")
    check(obj.nimbus.cycles_shift and all(abs(c + VOXEL / 2) < 1e-6 for c in obj.location),
          f"{label}: Cycles half-voxel shift on by default: location {tuple(obj.location)}")
    obj.nimbus.cycles_shift = False
    check(all(c == 0.0 for c in obj.location), f"{label}: shift off puts the object at the origin")
    obj.nimbus.cycles_shift = True
    path = bpy.path.abspath(obj.data.filepath)
    check(os.path.isfile(path) and path.endswith(".vdb"), f"{label}: the VDB exists ({path})")
    check(obj.data.grids.load() and "density" in [g.name for g in obj.data.grids],
          f"{label}: the grid 'density' loads ({obj.data.grids.error_message})")
    info = nimbus_info(program, path)
    grid = obj.data.grids["density"] if "density" in obj.data.grids else None
    check(grid is not None and info["voxel"] is not None and abs(grid.matrix_object[0][0] - info["voxel"]) < 1e-6
          and abs(info["voxel"] - VOXEL) < 1e-6, f"{label}: the grid's voxel is {VOXEL} m as the file's")
    bounds = mesh_bounds(obj)
    if check(bounds is not None and info["lo"] is not None, f"{label}: the grid has voxels and nimbus info a box"):
        lo, hi = (b - 0.5 * info["voxel"] for b in bounds)
        err = max(max(abs(a - b) for a, b in zip(lo, info["lo"])), max(abs(a - b) for a, b in zip(hi, info["hi"])))
        check(err <= info["voxel"], f"{label}: the voxels' bounds {np.round(lo, 1)}..{np.round(hi, 1)} match "
                                    f"the VDB's {info['lo']}..{info['hi']} within a voxel (off by {err:.1f} m)")
    if info["index"] is not None:
        # Blender's own box (object space): holds the active voxels' centres, within their 8^3 leaves.
        v, i = info["voxel"], info["index"]
        corners = np.array([tuple(c) for c in obj.bound_box])
        blo, bhi = corners.min(axis=0), corners.max(axis=0)
        inner_lo, inner_hi = np.array(i[:3]) * v, np.array(i[3:]) * v
        outer_lo, outer_hi = np.floor(np.array(i[:3]) / 8) * 8 * v, (np.floor(np.array(i[3:]) / 8) * 8 + 7) * v
        check(bool(np.all(blo <= inner_lo + 1e-3) and np.all(bhi >= inner_hi - 1e-3)
                   and np.all(blo >= outer_lo - 1e-3) and np.all(bhi <= outer_hi + 1e-3)),
              f"{label}: Blender's bounds {blo}..{bhi} hold the voxel centres {inner_lo}..{inner_hi} "
              f"within their leaves {outer_lo}..{outer_hi}")
    check_material(obj, label, program)
    return obj


def check_sequence(program, label):
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = 24, 1.0
    r = add(preset="cumulus-humilis", voxel_size=VOXEL, animated=True, frame_first=1, frame_last=3)
    check(r == {"FINISHED"}, f"{label}: an animated cloud of frames 1-3 finishes")
    vol = bpy.context.active_object.data
    check(vol.is_sequence and vol.frame_start == 1 and vol.frame_duration == 3 and vol.frame_offset == 0,
          f"{label}: the Volume is a sequence starting at frame 1, 3 frames")
    seen = []
    for frame in (1, 2, 3):
        scene.frame_set(frame)
        loaded = vol.grids.load()
        path = bpy.path.abspath(vol.grids.frame_filepath)
        seen.append(path)
        check(loaded and vol.grids.frame == frame and "density" in [g.name for g in vol.grids],
              f"{label}: frame {frame} loads its grid ({os.path.basename(path)})")
        t = nimbus_info(program, path)["time"]
        check(t is not None and abs(t - (frame - 1) / 24.0) < 1e-6, f"{label}: frame {frame}'s file is at t = {t} s "
                                                                      f"(expected {(frame - 1) / 24.0:.6f})")
    check(len(set(seen)) == 3 and all(os.path.isfile(p) for p in seen), f"{label}: a different file per frame")
    scene.frame_set(1)
    bpy.context.active_object.hide_render = True


class FakeModal:
    """Stands in for Blender's event loop around a modal generation: the window manager's progress
    bar and timer, the status bar, and events of a type."""

    def __init__(self):
        self.progress, self.ended, self.status = [], False, []
        wm = type("WM", (), {"progress_update": lambda _, v: self.progress.append(v),
                             "progress_end": lambda _: setattr(self, "ended", True),
                             "event_timer_remove": lambda _, timer: None})()
        ws = type("WS", (), {"status_text_set": lambda _, text: self.status.append(text)})()
        self.context = type("Ctx", (), {"window_manager": wm, "workspace": ws})()

    @staticmethod
    def event(kind):
        return type("Event", (), {"type": kind, "value": "PRESS"})()


def check_modal(label):
    """Generation on a thread of its own (the Add and Regenerate operators' modal path): the timer
    moves the progress bar until the job ends; Esc stops it within seconds and adds nothing."""
    from nimbus_clouds import generation, operators
    from nimbus_clouds.params import CloudParams

    def drive(op, first_event, limit_s):
        modal, t = FakeModal(), time.time()
        result = operators.step_modal(op, modal.context, modal.event(first_event), lambda c, job: {"FINISHED"})
        while result == {"PASS_THROUGH"} or result == {"RUNNING_MODAL"}:
            if time.time() - t > limit_s:
                op._running.cancel()
                op._running.wait()
                return None, modal, time.time() - t
            time.sleep(0.05)
            result = operators.step_modal(op, modal.context, modal.event("TIMER"), lambda c, job: {"FINISHED"})
        return result, modal, time.time() - t

    op = FakeOperator(preset="cumulus-humilis")
    job = operators.prepare(bpy.context, CloudParams(preset="cumulus-humilis", voxel_size=2.5, animated=True,
                                                     frame_first=1, frame_last=3))
    op._running, op._timer = generation.Running(job), None
    result, modal, took = drive(op, "TIMER", 300)
    check(result == {"FINISHED"} and modal.ended and all(os.path.isfile(p) for p in job.paths),
          f"{label}: a modal generation of 3 frames ends FINISHED with its files, the progress bar ended "
          f"({result}, {took:.1f} s)")
    check(modal.progress == sorted(modal.progress) and all(0.0 <= v <= 1.0 for v in modal.progress)
          and len(set(modal.progress)) >= 3 and modal.progress[-1] >= 0.6,
          f"{label}: its progress grows through at least 3 values within 0..1 "
          f"({sorted(set(round(v, 2) for v in modal.progress))})")

    op = FakeOperator(preset="cumulus-humilis")
    job = operators.prepare(bpy.context, CloudParams(preset="cumulus-humilis", voxel_size=1.5, seed=99))
    op._running, op._timer = generation.Running(job), None
    time.sleep(0.3)
    check(not op._running.done, f"{label}: a 1.5 m cumulus is still generating 0.3 s after its start")
    result, modal, took = drive(op, "ESC", 30)
    check(result == {"CANCELLED"} and any("WARNING" in k and "cancelled" in m for k, m in op.reports)
          and not os.path.exists(job.paths[0]) and took < 10.0,
          f"{label}: Esc cancels a 1.5 m cumulus in {took:.2f} s, no file, a warning ({result}, {op.reports})")


def check_refusals(label):
    from nimbus_clouds import cache, operators, preferences
    folder = cache.cache_folder()
    files_before = sorted(os.listdir(folder)) if os.path.isdir(folder) else []
    objects_before = len(bpy.data.objects)
    bad = [({"voxel_size": 0.001}, "voxel size"),
           ({"use_preset_seed": False, "seed": -1}, "seed"),
           ({"time": -1.0}, "time"),
           ({"animated": True, "frame_first": 5, "frame_last": 2}, "last frame"),
           ({"animated": True, "frame_first": 2000000, "frame_last": 2000001}, "Blender's frames end at 1048574"),
           ({"animated": True, "frame_first": 1, "frame_last": 2, "time": 5e8}, "time 5e+08 s"),
           ({"size": 0.0}, "size factor")]
    for given, name in bad:
        t = time.time()
        try:
            r = add(preset="cumulus-humilis", **given)
            raised = ""
        except RuntimeError as e:  # Blender turns an operator's error report into RuntimeError
            r, raised = None, str(e)
        took = time.time() - t
        check(r is None and "nimbus:" in raised and name in raised and took < 20.0,
              f"{label}: {given} refused naming '{name}' in {took:.2f} s: {raised.strip()!r}")
    fake = FakeOperator(preset="cumulus-humilis", voxel_size=0.001)
    result = operators.NIMBUS_OT_add_cloud.execute(fake, bpy.context)
    check(result == {"CANCELLED"} and any("ERROR" in k and "voxel size" in m for k, m in fake.reports),
          f"{label}: execute() returns CANCELLED with an ERROR report for 0.001 m ({result}, {fake.reports})")
    prefs = preferences.get(bpy.context)
    limit = prefs.memory_limit_gib
    prefs.memory_limit_gib = 0.001  # 1 MiB: below this cloud's 9 MB at 6 m
    try:
        add(preset="cumulus-humilis", voxel_size=6.0)
        raised = ""
    except RuntimeError as e:
        raised = str(e)
    prefs.memory_limit_gib = limit
    check("Memory limit" in raised, f"{label}: a plan over the memory limit preference is refused ({raised.strip()!r})")
    check(len(bpy.data.objects) == objects_before, f"{label}: no object was added by a refused call")
    files_after = sorted(os.listdir(folder)) if os.path.isdir(folder) else []
    check(files_after == files_before, f"{label}: no file was written by a refused call")


def check_after_refusals(program, label):
    """Blender still runs: a bigger cloud (size factor 2) and a regeneration."""
    base = bpy.context.scene.objects.get("nimbus cumulus-humilis")
    r = add(preset="cumulus-humilis", voxel_size=VOXEL, size=2.0)
    check(r == {"FINISHED"}, f"{label}: after the refusals, a cloud twice the size is added")
    big = bpy.context.active_object
    b1, b0 = mesh_bounds(big), mesh_bounds(base) if base else None
    if check(b1 is not None and b0 is not None, f"{label}: both clouds have voxels"):
        ratio = (b1[1][0] - b1[0][0]) / (b0[1][0] - b0[0][0])
        check(1.6 < ratio < 2.4, f"{label}: size factor 2 makes the cloud {ratio:.2f} times as wide")
    old = big.data.filepath
    big.nimbus.coverage = 0.5
    r = bpy.ops.nimbus.regenerate()
    check(r == {"FINISHED"} and big.data.filepath != old and os.path.isfile(bpy.path.abspath(big.data.filepath)),
          f"{label}: Regenerate with coverage 0.5 writes and loads a new file")
    big.hide_render = True


def check_render(obj, folder):
    scene = bpy.context.scene
    for o in scene.objects:
        o.hide_render = o is not obj and o.type == "VOLUME"
    cam = bpy.data.objects.new("test camera", bpy.data.cameras.new("test camera"))
    scene.collection.objects.link(cam)
    cam.location = (0.0, -2200.0, 1000.0)
    cam.rotation_euler = (math.radians(90.0), 0.0, 0.0)  # looking along +y, z up
    cam.data.sensor_fit = "HORIZONTAL"
    cam.data.angle = math.radians(40.0)
    cam.data.clip_end = 1e5
    scene.camera = cam
    sun = bpy.data.objects.new("test sun", bpy.data.lights.new("test sun", "SUN"))
    scene.collection.objects.link(sun)
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_mode = "QUATERNION"
    sun.rotation_quaternion = Vector((0.4, -0.6, 0.7)).normalized().to_track_quat("Z", "Y")  # front-lit from above
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = scene.cycles.volume_bounces = 16
    scene.render.film_transparent = True
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 32, 24, 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = os.path.join(folder, "render.exr")
    t = time.time()
    bpy.ops.render.render(write_still=True)
    print(f"render 32x24, 4 spp: {time.time() - t:.1f} s")
    img = bpy.data.images.load(scene.render.filepath)
    px = np.empty(img.size[0] * img.size[1] * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    px = px.reshape(-1, 4)
    lum = 0.2126 * px[:, 0] + 0.7152 * px[:, 1] + 0.0722 * px[:, 2]
    background = lum[px[:, 3] < 0.01]
    level = float(np.median(background)) if background.size else 0.0
    lit = int(np.sum(lum > level + 0.02))
    check(bool(np.all(np.isfinite(px))), "render: every pixel is finite")
    check(img.size[0] == 32 and img.size[1] == 24, f"render: 32x24 read back ({tuple(img.size)})")
    check(lit >= 0.05 * lum.size and float(lum.max()) > 0.05,
          f"render: the cloud is lit: {lit} of {lum.size} pixels above the background {level:.4f} + 0.02 "
          f"(brightest {float(lum.max()):.3f})")


def main():
    a = parse()
    if not check(os.path.isfile(a.nimbus_program) and os.access(a.nimbus_program, os.X_OK),
                 f"--nimbus-program {a.nimbus_program} is an executable file"):
        return
    if not check(os.path.isfile(os.path.join(a.repo, "blender", "nimbus_clouds", "__init__.py")),
                 f"--repo {a.repo} holds blender/nimbus_clouds"):
        return
    # A '%' in the cache folder's path: the sequences' frame field is formatted in their names alone.
    tmp = tempfile.mkdtemp(prefix="nimbus-blender-test-100%d%-")
    os.environ["XDG_CACHE_HOME"] = tmp  # unsaved .blend: the add-on's cache goes to $XDG_CACHE_HOME/nimbus-blender
    os.environ["NIMBUS_PROGRAM"] = a.nimbus_program
    sys.path.insert(0, os.path.join(a.repo, "blender"))
    if a.nimbus_python and os.path.isdir(a.nimbus_python):
        sys.path.insert(0, a.nimbus_python)
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)

    import addon_utils
    module = addon_utils.enable("nimbus_clouds", default_set=True, handle_error=lambda e: traceback.print_exc())
    if not check(module is not None and hasattr(bpy.ops.nimbus, "add_cloud"), "the add-on enables"):
        return
    from nimbus_clouds import backend_module, panel, preferences
    draw_funcs = getattr(bpy.types.VIEW3D_MT_volume_add.draw, "_draw_funcs", [])
    check(panel.menu_entry in draw_funcs, "Add > Volume has the 'nimbus Cloud' entry")
    check(hasattr(bpy.types, "VIEW3D_PT_nimbus_cloud") and panel.VIEW3D_PT_nimbus_cloud.bl_category == "nimbus",
          "the sidebar has a 'nimbus' tab panel")

    backends = []
    if backend_module.import_module() is not None:
        backends.append(("MODULE", "module"))
    else:
        print(f"note: the nimbus module does not import from '{a.nimbus_python}'; testing the program only")
    backends.append(("PROGRAM", "program"))
    prefs = preferences.get(bpy.context)
    first_still = None
    for mode, label in backends:
        prefs.backend = mode
        obj = check_still(a.nimbus_program, label)
        if first_still is None and obj is not None:
            check_panel(obj)
        first_still = first_still or obj
        check_sequence(a.nimbus_program, label)
        check_refusals(label)
        check_modal(label)
        check_after_refusals(a.nimbus_program, label)
    if first_still is not None:
        check_render(first_still, tmp)
    if not FAILED:
        shutil.rmtree(tmp, ignore_errors=True)
    else:
        print(f"files kept in {tmp}")


if __name__ == "__main__":
    try:
        main()
    except Exception:
        traceback.print_exc()
        FAILED.append("an exception escaped the test")
    print(f"{len(FAILED)} check(s) failed" if FAILED else "all checks passed", flush=True)
    sys.exit(1 if FAILED else 0)
