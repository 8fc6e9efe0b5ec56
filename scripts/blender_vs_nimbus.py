# Measures Cycles (through the nimbus_clouds add-on's material) against nimbus's path tracer on one cloud.
#
#   blender -b --factory-startup --python scripts/blender_vs_nimbus.py -- --nimbus build/nimbus \
#       [--nimbus-python build/python] [--out DIR] [--png docs/blender-vs-nimbus.png] [options below]
#
# Both render the same VDB, camera and sun (nimbus's flags and Blender are both Z up, x east, y
# north: the vectors pass unchanged), clouds alone over black, twice each with different seeds. The
# error is the relative RMSE of RGB over covered pixels (nimbus alpha > 0.01) with both renders' noise
# taken out: sum((A - B)^2) - sum(var A) - sum(var B), over sum(A^2) - sum(var A), where A and B are
# the means of the two renders and var = ((r1 - r2) / 2)^2 per pixel and channel.
import argparse
import math
import os
import subprocess
import sys
import time

import bpy
import numpy as np
from mathutils import Matrix, Vector

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SUN_IRRADIANCE = 3.0  # W/m^2 per channel: nimbus's default sun (render/core/.../light.hpp), --scene none


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_vs_nimbus.py")
    p.add_argument("--nimbus", required=True, help="the nimbus program (renders the reference)")
    p.add_argument("--nimbus-python", default="", help="folder holding the nimbus module (optional)")
    p.add_argument("--out", default="/tmp/nimbus-blender-vs")
    p.add_argument("--png", default="", help="also write a side-by-side PNG (nimbus | Cycles per sun)")
    p.add_argument("--preset", default="cumulus-humilis")
    p.add_argument("--voxel-size", type=float, default=12.0)
    p.add_argument("--res", default="160x90")
    p.add_argument("--eye", default="0,-2200,1050")
    p.add_argument("--look-at", default="0,0,1000")
    p.add_argument("--up", default="0,0,1")
    p.add_argument("--fov", type=float, default=30.0)
    p.add_argument("--sun", action="append", help="X,Y,Z towards the sun, Z up (repeatable; default front and back)")
    p.add_argument("--nimbus-spp", type=int, default=1024)
    p.add_argument("--cycles-spp", type=int, default=512)
    p.add_argument("--bounces", type=int, default=1024, help="Cycles volume (and total) bounces")
    p.add_argument("--step-rate", type=float, default=1.0, help="Cycles volume step rate (1: one voxel)")
    p.add_argument("--max-steps", type=int, default=4096, help="Cycles volume max steps")
    p.add_argument("--material", choices=("addon", "two-scatter"), default="addon",
                   help="two-scatter: the naive tree (two Volume Scatter nodes of densities 0.8 and 0.2 x albedo x "
                        "sigma_t) that Cycles 3.4 renders too bright (docs/blender.md)")
    p.add_argument("--reuse", action="store_true", help="measure the EXRs already in --out (no rendering)")
    p.add_argument("--cycles-shift", choices=("on", "off"), default="on",
                   help="the add-on's Cycles half-voxel shift (on: where nimbus puts the voxels; "
                        "off: object at the origin)")
    a = p.parse_args(argv)
    a.sun = a.sun or ["0.5,-0.62,0.6", "-0.35,0.82,0.45"]
    return a


def vec(text):
    return Vector(float(v) for v in text.split(","))


def enable_addon(nimbus, nimbus_python):
    sys.path.insert(0, os.path.join(REPO, "blender"))
    if nimbus_python:
        sys.path.insert(0, nimbus_python)
    os.environ.setdefault("NIMBUS_PROGRAM", nimbus)
    import addon_utils
    addon_utils.enable("nimbus_clouds", default_set=True, handle_error=None)
    import nimbus_clouds
    return nimbus_clouds


def add_cloud(a):
    bpy.ops.nimbus.add_cloud(preset=a.preset, voxel_size=a.voxel_size, cycles_shift=a.cycles_shift == "on")
    obj = bpy.context.active_object
    return obj, bpy.path.abspath(obj.data.filepath)


def two_scatter_tree(mat):
    """The naive dual-lobe tree: a Volume Scatter node per lobe, densities w x albedo x sigma_t."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    sigma_t, albedo = nodes["nimbus sigma_t"], nodes["nimbus albedo"]
    add, out = nodes["nimbus add"], nodes["nimbus output"]
    for n in [n for n in nodes if n.bl_idname == "ShaderNodeVolumeScatter"]:
        nodes.remove(n)
    add2 = nodes.new("ShaderNodeAddShader")
    for k, (g, w) in enumerate(((0.7, 0.8), (-0.25, 0.2))):
        density = nodes.new("ShaderNodeMath")
        density.operation = "MULTIPLY"
        links.new(sigma_t.outputs[0], density.inputs[0])
        density.inputs[1].default_value = w
        scatter = nodes.new("ShaderNodeVolumeScatter")
        scatter.inputs["Anisotropy"].default_value = g
        links.new(albedo.outputs[0], scatter.inputs["Color"])
        links.new(density.outputs[0], scatter.inputs["Density"])
        links.new(scatter.outputs[0], add2.inputs[k])
    links.new(add2.outputs[0], add.inputs[0])
    links.new(add.outputs[0], out.inputs["Volume"])


def set_up_scene(a, w, h):
    scene = bpy.context.scene
    for o in list(scene.objects):
        if o.type != "VOLUME":
            bpy.data.objects.remove(o)
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = a.bounces
    c.volume_bounces = a.bounces
    c.transparent_max_bounces = 64
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.volume_step_rate = a.step_rate
    c.volume_max_steps = a.max_steps
    c.pixel_filter_type = "BOX"
    c.filter_width = 0.01  # Cycles' least: the pixel centre, as nimbus's one ray per pixel sample
    scene.render.film_transparent = True
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.exposure = 0.0
    scene.view_settings.look = "None"
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world

    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    eye, look, up = (vec(t) for t in (a.eye, a.look_at, a.up))
    f = (look - eye).normalized()
    r = f.cross(up).normalized()
    u = r.cross(f)
    m = Matrix((r, u, -f)).transposed().to_4x4()
    m.translation = eye
    cam.matrix_world = m
    cam.data.sensor_fit = "HORIZONTAL"
    cam.data.angle = math.radians(a.fov)
    cam.data.clip_start, cam.data.clip_end = 0.1, 1e6
    scene.camera = cam

    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    scene.collection.objects.link(sun)
    sun.data.energy = SUN_IRRADIANCE  # W/m^2: Cycles' sun strength is irradiance
    sun.data.color = (1.0, 1.0, 1.0)
    sun.data.angle = 0.0  # nimbus's sun is a direction, not a disc
    return scene, sun


def point_sun(sun, to_sun):
    d = vec(to_sun).normalized()
    sun.rotation_mode = "QUATERNION"
    sun.rotation_quaternion = d.to_track_quat("Z", "Y")  # the light travels along its -Z


def render_cycles(scene, seed, samples, path):
    scene.cycles.seed = seed
    scene.cycles.samples = samples
    scene.render.filepath = path
    t = time.time()
    bpy.ops.render.render(write_still=True)
    return time.time() - t


def render_nimbus(a, vdb, sun, seed, path):
    argv = [a.nimbus, "render", vdb, "--scene", "none", "--method", "pathtrace", "--spp", str(a.nimbus_spp),
            "--seed", str(seed), "--eye", a.eye, "--look-at", a.look_at, "--up", a.up, "--fov", repr(a.fov),
            "--res", a.res, "--sun", sun, "-o", path]
    t = time.time()
    r = subprocess.run(argv, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"nimbus render failed ({r.returncode}): {r.stderr.strip()[-500:]}")
    return time.time() - t, argv


def read_exr(path):
    img = bpy.data.images.load(path, check_existing=False)
    w, h = img.size
    px = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    return px.reshape(h, w, 4)


def measure(n1, n2, c1, c2):
    """Noise-corrected relative RMSE (and raw, bias, alpha RMSE) of Cycles against nimbus."""
    A, B = (n1 + n2) / 2, (c1 + c2) / 2
    mask = A[..., 3] > 0.01
    a, b = A[mask][:, :3].astype(np.float64), B[mask][:, :3].astype(np.float64)
    var_a = (((n1 - n2) / 2)[mask][:, :3].astype(np.float64)) ** 2
    var_b = (((c1 - c2) / 2)[mask][:, :3].astype(np.float64)) ** 2
    err, ref = np.sum((b - a) ** 2), np.sum(a * a)
    # Per pixel and channel, (B - A)^2 - var A - var B estimates the squared systematic difference;
    # their sum's standard error (from their spread) bounds what the noise leaves unknown.
    terms = (b - a) ** 2 - var_a - var_b
    signal = ref - var_a.sum()
    corrected = math.sqrt(max(0.0, terms.sum()) / signal)
    upper = math.sqrt(max(0.0, terms.sum() + 2.0 * math.sqrt(terms.size * terms.var())) / signal)
    return {"pixels": int(mask.sum()), "rel_rmse": corrected, "rel_rmse_upper95": upper,
            "raw_rel_rmse": math.sqrt(err / ref),
            "noise_nimbus": math.sqrt(var_a.sum() / ref), "noise_cycles": math.sqrt(var_b.sum() / ref),
            "bias": float(np.sum(b - a) / np.sum(a)),
            "alpha_rmse": float(np.sqrt(np.mean((B[mask][:, 3] - A[mask][:, 3]) ** 2)))}


def tone(rgb, scale):
    x = np.clip(rgb * scale, 0.0, None)
    x = x / (1.0 + x)  # Reinhard
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def write_png(path, rows, zoom=2):
    """rows: [(nimbus, cycles)] images (h, w, 4), bottom-up; nimbus | Cycles side by side, one row per sun,
    each pixel drawn zoom x zoom."""
    rows = [tuple(np.repeat(np.repeat(img, zoom, 0), zoom, 1) for img in row) for row in rows]
    h, w = rows[0][0].shape[:2]
    gap = 2
    W, H = 2 * w + gap, len(rows) * h + (len(rows) - 1) * gap
    canvas = np.ones((H, W, 4), dtype=np.float32)
    for i, (n, c) in enumerate(rows):
        scale = 1.0 / max(1e-6, float(np.percentile(0.2126 * n[..., 0] + 0.7152 * n[..., 1] + 0.0722 * n[..., 2], 99)))
        y0 = (len(rows) - 1 - i) * (h + gap)  # Blender's rows run bottom-up
        for j, img in enumerate((n, c)):
            x0 = j * (w + gap)
            canvas[y0:y0 + h, x0:x0 + w, :3] = tone(img[..., :3], scale)
            canvas[y0:y0 + h, x0:x0 + w, 3] = 1.0
    png = bpy.data.images.new("side-by-side", W, H, alpha=False)
    png.pixels.foreach_set(canvas.ravel())
    png.filepath_raw = path
    png.file_format = "PNG"
    png.save()
    bpy.data.images.remove(png)


def main():
    a = parse()
    os.makedirs(a.out, exist_ok=True)
    os.environ.setdefault("XDG_CACHE_HOME", os.path.join(a.out, "cache"))
    enable_addon(a.nimbus, a.nimbus_python)
    w, h = (int(v) for v in a.res.split("x"))
    obj, vdb = add_cloud(a)
    if a.material == "two-scatter":
        two_scatter_tree(obj.data.materials[0])
    scene, sun = set_up_scene(a, w, h)
    print(f"cloud: {a.preset} at {a.voxel_size:g} m, {vdb}; backend {obj.nimbus.backend_used}; "
          f"object at {tuple(obj.location)} (Cycles half-voxel shift {a.cycles_shift}); material {a.material}")
    rows, results = [], []
    for k, s in enumerate(a.sun):
        point_sun(sun, s)
        n = [os.path.join(a.out, f"nimbus-sun{k}-seed{seed}.exr") for seed in (1, 2)]
        c = [os.path.join(a.out, f"cycles-sun{k}-seed{seed}.exr") for seed in (1, 2)]
        if a.reuse and all(os.path.isfile(p) for p in n + c):
            tn, tc = [(0.0, ["(reused)"])] * 2, [0.0, 0.0]
        else:
            tn = [render_nimbus(a, vdb, s, seed, path) for seed, path in zip((1, 2), n)]
            tc = [render_cycles(scene, seed, a.cycles_spp, path) for seed, path in zip((1, 2), c)]
        imgs = [read_exr(p) for p in n + c]
        m = measure(*imgs)
        results.append((s, m))
        rows.append(((imgs[0] + imgs[1]) / 2, (imgs[2] + imgs[3]) / 2))
        print(f"sun {s}: nimbus {a.nimbus_spp} spp x2: {tn[0][0]:.1f} s + {tn[1][0]:.1f} s; "
              f"Cycles {a.cycles_spp} spp x2: {tc[0]:.1f} s + {tc[1]:.1f} s")
        print(f"  nimbus command: {' '.join(tn[0][1])}")
        print(f"  relative RMSE less noise {100 * m['rel_rmse']:.2f} % "
              f"(95 % upper bound {100 * m['rel_rmse_upper95']:.2f} %; "
              f"raw {100 * m['raw_rel_rmse']:.2f} %, "
              f"noise of the means: nimbus {100 * m['noise_nimbus']:.2f} %, Cycles {100 * m['noise_cycles']:.2f} %), "
              f"bias {100 * m['bias']:+.2f} %, alpha RMSE {m['alpha_rmse']:.4f}, {m['pixels']} covered pixels")
    if a.png:
        write_png(a.png, rows)
        print(f"wrote {a.png}")
    worst = max(m["rel_rmse"] for _, m in results)
    bound = max(m["rel_rmse_upper95"] for _, m in results)
    raw = max(m["raw_rel_rmse"] for _, m in results)
    print(f"RESULT worst relative RMSE less noise: {100 * worst:.2f} % (95 % upper bound {100 * bound:.2f} %; "
          f"raw, noise included: {100 * raw:.2f} %)")


if __name__ == "__main__":
    try:
        main()
    except Exception:
        import traceback
        traceback.print_exc()
        sys.exit(1)
