#!/usr/bin/python3
"""Writes the fuzz seed corpus kept in the repository (tests/fuzz/corpus/):

    make_seed_corpus.py --nimbus BIN [--out tests/fuzz/corpus] [--only CORPUS...]

  params_json/  inputs of fuzz_params.cpp: "[preset:NAME\\n]PARAMS[\\0SET...]" (see there): whole
                preset documents, "cloud" overrides, --set arguments, and files that must be
                refused cleanly;
  vdb/          inputs of fuzz_vdb.cpp: small intact files from pyopenvdb (make_hostile_vdbs.py's
                kinds) and from nimbus (sealed), and damaged copies that must be refused cleanly;
  exr/          inputs of fuzz_exr.cpp: a render written by nimbus (ZIP, half RGBA, metadata),
                uncompressed scan-line and tiled files written here from the OpenEXR file layout,
                and damaged or hostile copies (cut, a flipped byte, a data window or attribute size
                beyond what the file holds, another compression, no R, G, B or A);
  png/          inputs of fuzz_png.cpp: nimbus's preview of that render (8-bit RGB), PNGs written
                here (grey of 1, 8 and 16 bits, palette with transparency, grey and alpha, RGBA,
                interlaced), and damaged or hostile copies (cut, a bad CRC, an IHDR declaring
                8192 x 8192 pixels or none).

Deterministic (the generator's seeds are fixed), so rerunning it rewrites the same bytes; inputs the
fuzzer found and that now pass (e.g. vdb/nodes-without-active-voxels.vdb) are kept beside them. Every
file here must pass the replay (Fuzz.*CorpusReplay); inputs that break the code go to
tests/fuzz/findings/ instead.
"""
import argparse
import json
import os
import random
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_hostile_vdbs as hostile  # noqa: E402

PRESETS = os.path.join(HERE, "..", "..", "volume", "presets")


def params_seeds():
    seeds = {}
    for name in ["steam", "cumulus-congestus", "cumulus-field", "cirrus-fibratus"]:
        with open(os.path.join(PRESETS, name + ".json"), "rb") as f:
            seeds["preset-%s.json" % name] = b"preset:" + name.encode() + b"\n" + f.read()
    j = lambda o: json.dumps(o).encode()  # noqa: E731
    seeds.update({
        "empty-object.json": b"{}",
        "coverage.json": j({"coverage": 0.5, "density": 0.8}),
        "noise-wavelet.json": j({"noise": "wavelet", "octaves": 3, "lacunarity": 2.5, "gain": 0.4}),
        "shapes.json": j({"shapes": [
            {"kind": "ellipsoid", "center": [0, 0, 900], "size": [400, 300, 250], "falloff": 0.5, "weight": 1},
            {"kind": "capsule", "center": [0, 0, 800], "end": [300, 0, 900], "size": [100, 100, 100],
             "falloff": 1, "weight": 0.7, "fade_up": 1.2, "roughness": 0.3, "roughness_seed": 5},
            {"kind": "slab", "center": [0, 0, 1000], "size": [2000, 2000, 100], "falloff": 0.2, "weight": 0.5},
            {"kind": "lens", "center": [0, 0, 3000], "size": [900, 900, 200], "falloff": 0.4, "weight": 1}]}),
        "field.json": b"preset:cumulus-field\n" + j({"field": {
            "center": [0, 0], "size": [4000, 4000], "coverage": 0.3, "size_exponent": 1.8,
            "min_diameter": 200, "max_diameter": 900, "depth_scale": 1.0, "roughness": 0.2, "seed": 9,
            "species": {"humilis": 0.6, "mediocris": 0.4}}}),
        "whole-document.json": b"preset:smoke\n" + j({"voxel_size": 0.05, "cloud": {"seed": 4, "wind": [1, 0, 0.5]}}),
        "misc-keys.json": j({"shear": [0.1, -0.2], "stretch": 2, "stretch_altitude": 1000,
                             "stretch_direction": [1, 1], "cauliflower": 0.5, "cauliflower_frequency": 0.01,
                             "furrows": 0.2, "furrow_frequency": 0.02, "sine": True, "evolution": 0.1,
                             "temperature_base": 300, "temperature_height": 2000, "seed": 4294967295}),
        "sets.json": j({"coverage": 0.4}) + b"\0coverage=0.3\0shapes.0.size=[500, 400, 300]\0noise=worley"
                     b"\0wind=[1,2,3]",
        "set-unknown-key.json": b"{}\0nope=1",
        "set-no-equals.json": b"{}\0coverage",
        "set-bad-index.json": b"{}\0shapes.7.size=[1,1,1]",
        "preset-unknown.json": b"preset:nonesuch\n{}",
        "refused-not-json.json": b"{\"coverage\": 0.5,,}",
        "refused-array.json": b"[1, 2, 3]",
        "refused-wrong-type.json": j({"coverage": "lots"}),
        "refused-out-of-range.json": j({"octaves": 99, "gain": 7}),
        "refused-nan.json": b"{\"coverage\": NaN}",
        "refused-huge-number.json": b"{\"frequency\": 1e400}",
        "refused-unknown-key.json": j({"colour": "grey"}),
        "refused-shape-kind.json": j({"shapes": [{"kind": "torus"}]}),
        "refused-no-shapes.json": j({"shapes": []}),
        "refused-cloud-not-object.json": j({"cloud": [1]}),
        "refused-empty-file.json": b"",
        "refused-bad-utf8.json": b"{\"\xff\xfe\": 1}",
    })
    return seeds


# A level set (110 KB) is left to the command-line driver: the corpus stays small.
VDB_KINDS = ["fog_small", "fog_half", "multi_grid", "vec3_only", "bool_only", "int_only",
             "empty_grid", "no_grids", "nan_inf", "negative", "nonuniform_scale", "frustum", "extent_overflow",
             "zero_scale"]


def vdb_seeds(nimbus, tmp):
    seeds = {}
    for k in VDB_KINDS:
        seeds["%s.vdb" % k] = hostile.write_pyopenvdb(k, 1, tmp)
    for name, args in [("nimbus-noise.vdb", ["noise", "--kind", "value", "--res", "8"]),
                       ("nimbus-steam.vdb", ["generate", "--preset", "steam", "--voxel-size", "0.05"])]:
        path = os.path.join(tmp, name)
        subprocess.run([nimbus] + args + ["-o", path], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        with open(path, "rb") as f:
            seeds[name] = f.read()
    rng = random.Random(7)
    for base, how in [("fog_small.vdb", "trunc"), ("fog_small.vdb", "metalen"), ("fog_half.vdb", "offsets"),
                      ("nimbus-noise.vdb", "flip1"), ("nimbus-noise.vdb", "trunc"), ("nimbus-steam.vdb", "garble16")]:
        data, _ = hostile.damage(seeds[base], how, rng)
        seeds["damaged-%s-%s" % (how, base)] = data
    return seeds


def nimbus_render(nimbus, tmp):
    """A 16 x 9 reference render (CPU only) as nimbus writes it: the EXR and its PNG preview."""
    exr, png = os.path.join(tmp, "render.exr"), os.path.join(tmp, "render.png")
    subprocess.run([nimbus, "render", "--scene", "open", "--method", "reference", "--res", "16x9", "-o", exr,
                    "--preview", png], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(exr, "rb") as f, open(png, "rb") as g:
        return f.read(), g.read()


# EXR files written from the OpenEXR file layout (docs/OpenEXRFileLayout in OpenEXR): the magic
# number, the version field, attributes (name, type, size, value), a 0 byte, the chunk offsets,
# the chunks. Uncompressed, so that no compressor is needed here.
def exr_attribute(name, type_name, value):
    return name.encode() + b"\0" + type_name.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr_header(channels, w, h, tiles=None):
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", t, 0, 1, 1) for c, t in channels) + b"\0"
    box = struct.pack("<4i", 0, 0, w - 1, h - 1)
    attrs = [exr_attribute("channels", "chlist", chlist), exr_attribute("compression", "compression", b"\0"),
             exr_attribute("dataWindow", "box2i", box), exr_attribute("displayWindow", "box2i", box),
             exr_attribute("lineOrder", "lineOrder", b"\0"),
             exr_attribute("pixelAspectRatio", "float", struct.pack("<f", 1)),
             exr_attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)),
             exr_attribute("screenWindowWidth", "float", struct.pack("<f", 1))]
    if tiles:
        attrs.append(exr_attribute("tiles", "tiledesc", struct.pack("<IIB", tiles, tiles, 0)))
    version = 2 | (0x200 if tiles else 0)
    return struct.pack("<ii", 20000630, version) + b"".join(attrs) + b"\0"


def exr_samples(channels, xs, y):
    """One row's samples of pixels xs, channel after channel (names sorted, as OpenEXR stores them)."""
    out = b""
    for i, (c, t) in enumerate(sorted(channels)):
        for x in xs:
            v = ((x * 7 + y * 3 + i) % 9) / 8.0
            out += struct.pack("<e", v) if t == 1 else struct.pack("<f", v) if t == 2 else struct.pack("<I", x + y)
    return out


def exr_scanline(channels, w, h):
    header = exr_header(channels, w, h)
    chunks = [struct.pack("<i", y) + struct.pack("<i", len(d)) + d
              for y in range(h) for d in [exr_samples(channels, range(w), y)]]
    offset = len(header) + 8 * h
    table = b""
    for c in chunks:
        table += struct.pack("<Q", offset)
        offset += len(c)
    return header + table + b"".join(chunks)


def exr_tiled(channels, w, h, tile):
    header = exr_header(channels, w, h, tiles=tile)
    chunks = []
    for ty in range((h + tile - 1) // tile):
        for tx in range((w + tile - 1) // tile):
            xs = range(tx * tile, min(w, (tx + 1) * tile))
            d = b"".join(exr_samples(channels, xs, y) for y in range(ty * tile, min(h, (ty + 1) * tile)))
            chunks.append(struct.pack("<4i", tx, ty, 0, 0) + struct.pack("<i", len(d)) + d)
    offset = len(header) + 8 * len(chunks)
    table = b""
    for c in chunks:
        table += struct.pack("<Q", offset)
        offset += len(c)
    return header + table + b"".join(chunks)


def exr_patch(data, name, type_name, at, value):
    """`data` with the bytes at `at` of attribute name's value (after its size) replaced."""
    key = name.encode() + b"\0" + type_name.encode() + b"\0"
    i = data.index(key) + len(key) + 4 + at
    return data[:i] + value + data[i + len(value):]


def exr_seeds(render):
    rgba = [("A", 1), ("B", 1), ("G", 1), ("R", 1)]
    seeds = {
        "nimbus-render-16x9.exr": render,
        "none-rgba-half-5x3.exr": exr_scanline(rgba, 5, 3),
        "none-rgb-float-uint-3x2.exr": exr_scanline([("B", 2), ("G", 2), ("R", 2), ("id", 0)], 3, 2),
        "none-tiled-4x4-tiles-9x6.exr": exr_tiled(rgba, 9, 6, 4),
        "refused-luminance-only.exr": exr_scanline([("Y", 1)], 4, 2),
    }
    size = struct.pack("<i", 0x7fffffff)
    seeds.update({
        "damaged-cut-half.exr": render[:len(render) // 2],
        "damaged-flipped-byte.exr": render[:len(render) - 40] + bytes([render[-40] ^ 0x5a]) + render[len(render) - 39:],
        "damaged-piz-labelled.exr": exr_patch(render, "compression", "compression", 0, b"\x04"),
        "refused-window-8192x8192.exr": exr_patch(render, "dataWindow", "box2i", 8, struct.pack("<2i", 8191, 8191)),
        "refused-comments-2gb.exr": exr_patch(render, "comments", "string", -4, size),
        "refused-tiles-32767.exr": exr_patch(seeds["none-tiled-4x4-tiles-9x6.exr"], "tiles", "tiledesc", 0,
                                             struct.pack("<II", 32767, 32767)),
    })
    return seeds


# PNG files written here (PNG specification: the signature, then chunks of length, type, data and
# the CRC-32 of type and data; the image data one zlib stream of filtered rows).
def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png_file(w, h, depth, colour, rows, extra=b"", interlace=0):
    ihdr = struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, interlace)
    raw = b"".join(b"\0" + r for r in rows)  # filter type 0 (None) on every row
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + extra + png_chunk(b"IDAT", zlib.compress(raw, 9)) +
            png_chunk(b"IEND", b""))


def png_grey8(w, h, interlace=0):
    pixels = [[(x * 37 + y * 11) % 256 for x in range(w)] for y in range(h)]
    if not interlace:
        return png_file(w, h, 8, 0, [bytes(r) for r in pixels])
    # Adam7: seven passes of the pixels at these starts and steps (PNG specification 8.2).
    rows = []
    for x0, y0, dx, dy in [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2),
                           (0, 1, 1, 2)]:
        if x0 < w:
            rows += [bytes(pixels[y][x] for x in range(x0, w, dx)) for y in range(y0, h, dy)]
    return png_file(w, h, 8, 0, rows, interlace=1)


def png_seeds(preview):
    bits = [bytes([0b10110010, 0b01011100]) for _ in range(4)]  # 16 x 4 pixels of 1 bit
    seeds = {
        "nimbus-preview-16x9.png": preview,
        "grey8-12x7.png": png_grey8(12, 7),
        "grey8-interlaced-11x9.png": png_grey8(11, 9, interlace=1),
        "grey1-16x4.png": png_file(16, 4, 1, 0, bits),
        "grey16-3x2.png": png_file(3, 2, 16, 0, [struct.pack(">3H", 0, 30000, 65535), struct.pack(">3H", 1, 2, 3)]),
        "grey-alpha8-3x2.png": png_file(3, 2, 8, 4, [bytes([0, 255, 128, 128, 255, 0]),
                                                     bytes([9, 9, 200, 50, 70, 255])]),
        "rgba8-2x2.png": png_file(2, 2, 8, 6, [bytes([255, 0, 0, 255, 0, 255, 0, 128]),
                                               bytes([0, 0, 255, 0, 9, 9, 9, 9])]),
        "palette2-4x2-trns.png": png_file(4, 2, 2, 3, [bytes([0b00011011]), bytes([0b11100100])],
                                          extra=png_chunk(b"PLTE", bytes([0, 0, 0, 90, 90, 90, 180, 180, 180,
                                                                          255, 255, 255]))
                                          + png_chunk(b"tRNS", bytes([255, 128]))),
    }
    grey = seeds["grey8-12x7.png"]
    big_ihdr = struct.pack(">IIBBBBB", 8192, 8192, 8, 0, 0, 0, 0)
    none_ihdr = struct.pack(">IIBBBBB", 0, 7, 8, 0, 0, 0, 0)
    seeds.update({
        "damaged-cut.png": grey[:len(grey) - 20],
        "damaged-idat-crc.png": grey[:-16] + bytes([grey[-16] ^ 1]) + grey[-15:],
        "refused-ihdr-8192x8192.png": grey[:8] + png_chunk(b"IHDR", big_ihdr) + grey[33:],
        "refused-ihdr-no-pixels.png": grey[:8] + png_chunk(b"IHDR", none_ihdr) + grey[33:],
        "refused-not-png.png": b"GIF89a not a PNG",
    })
    return seeds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nimbus", required=True)
    ap.add_argument("--out", default=os.path.join(HERE, "corpus"))
    ap.add_argument("--only", nargs="+", choices=["params_json", "vdb", "exr", "png"],
                    help="rewrite these corpora only (default: all)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        makers = {"params_json": params_seeds, "vdb": lambda: vdb_seeds(a.nimbus, tmp),
                  "exr": lambda: exr_seeds(nimbus_render(a.nimbus, tmp)[0]),
                  "png": lambda: png_seeds(nimbus_render(a.nimbus, tmp)[1])}
        for sub in a.only or list(makers):
            seeds = makers[sub]()
            d = os.path.join(a.out, sub)
            os.makedirs(d, exist_ok=True)
            for name, data in sorted(seeds.items()):
                with open(os.path.join(d, name), "wb") as f:
                    f.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
