#!/usr/bin/python3
"""Render every preset from the side and from below, for docs/volume.md.

Writes docs/presets/NAME-side.png and NAME-below.png (nimbus render --preset, sky scene), and
docs/presets.png, the sheet of them all. Cameras come
from each preset's bounds (nimbus.plan). Run from the repository root after building with
-DNIMBUS_BUILD_PYTHON=ON:
    PYTHONPATH=build-test/python scripts/render-preset-sheet.py [build-test/nimbus]
SHEET_NAMES="a b" re-renders those presets alone and composes the sheet from the other pictures.
"""
import math
import os
import struct
import subprocess
import sys
import zlib

import nimbus

PROGRAM = sys.argv[1] if len(sys.argv) > 1 else "build-test/nimbus"
OUT = "docs/presets"
RES = (320, 200)
SIDE_FOV, BELOW_FOV = 50.0, 80.0


def cameras(lo, hi, body):
    """Side: the whole box. Below: up at the base under the body (the first shape's centre, else the box's)."""
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    w, h = max(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]
    aspect = RES[0] / RES[1]
    d = 1.1 * max(w, aspect * h) / (2 * math.tan(math.radians(SIDE_FOV / 2)))
    side = ((c[0], c[1] - d, c[2]), tuple(c), SIDE_FOV)  # Z up, as the flags
    s = min(w, 1.5 * h)  # an anvil or a layer is seen from under its middle, not from its far edge
    ground = max(lo[2] - 0.6 * s, 0.02 * h)  # below the base, above the ground plane
    b = body or c
    below = ((b[0] - 0.15 * s, b[1] - 0.3 * s, ground), (b[0], b[1], lo[2]), BELOW_FOV)
    return {"side": side, "below": below}


def render(name, voxel_m, view, eye, look, fov):
    path = f"{OUT}/{name}-{view}.png"
    fmt = lambda v: ",".join(f"{x:.4g}" for x in v)
    extra = []
    if voxel_m < 1:  # steam and smoke are metres across: as dense per voxel as a cloud at 20 m voxels
        extra = ["--cloud-extinction", f"{0.04 * 20 / voxel_m:.4g}"]
    subprocess.run([PROGRAM, "render", "--preset", name, "--eye", fmt(eye), "--look-at", fmt(look), "--fov", str(fov),
                    "--res", f"{RES[0]}x{RES[1]}", "-o", f"/tmp/nimbus-sheet-{name}-{view}.exr", "--preview", path] + extra,
                   check=True, stdout=subprocess.DEVNULL)
    return path


def main():
    os.makedirs(OUT, exist_ok=True)
    rows = []
    only = os.environ.get("SHEET_NAMES", "").split()  # re-render these alone
    for name in nimbus.presets():
        plan = nimbus.plan(name)
        lo, hi = plan["bounds_m"]
        shapes = nimbus.preset(name)["cloud"].get("shapes") or [{}]
        views = cameras(lo, hi, shapes[0].get("center"))
        if only and name not in only:  # compose the sheet from the pictures already rendered
            rows.append([f"{OUT}/{name}-{v}.png" for v in ("side", "below")])
            continue
        rows.append([render(name, plan["voxel_size"], v, *views[v]) for v in ("side", "below")])
        print(name, "done", flush=True)
    write_png("docs/presets.png", sheet([read_png(p) for row in rows for p in row], columns=4))


def read_png(path):
    """An 8-bit RGB or RGBA, non-interlaced PNG (what nimbus writes) as (width, height, rows of RGB bytes)."""
    data = open(path, "rb").read()
    pos, idat, info = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            info = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, colour, _, _, interlace = info
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"{path}: only 8-bit RGB(A) non-interlaced PNG")
    bpp = 3 if colour == 2 else 4
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        rows.append(bytes(line) if bpp == 3 else bytes(v for k, v in enumerate(line) if k % 4 != 3))
    return w, h, rows


def sheet(images, columns):
    """Equal-sized images in a grid, left to right, top to bottom; black where none is left."""
    w, h = images[0][0], images[0][1]
    grid = [images[i:i + columns] for i in range(0, len(images), columns)]
    rows = []
    for line in grid:
        for y in range(h):
            rows.append(b"".join(img[2][y] for img in line) + bytes(3 * w * (columns - len(line))))
    return w * columns, h * len(grid), rows


def write_png(path, image):
    w, h, rows = image
    chunk = lambda kind, body: struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(b"".join(b"\x00" + r for r in rows), 9)) + chunk(b"IEND", b"")
    tmp = path + ".tmp"
    open(tmp, "wb").write(data)
    os.replace(tmp, path)

if __name__ == "__main__":
    main()
