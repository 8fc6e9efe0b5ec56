#!/usr/bin/python3
"""Writes damaged and foreign VDB files for the fuzz suite (tests/fuzz, docs/reliability-fuzz.md).

    make_hostile_vdbs.py OUTDIR --count N --seed S [--nimbus BIN] [--kinds a,b] [--damages a,b]

Base files ("kinds") are written by pyopenvdb (python3-openvdb, Debian's /usr/bin/python3), so
they carry no nimbus seal: fog volumes, a level set, negative, huge and non-finite values, grids
of other value types, empty files, extents that overflow int32, odd transforms, a huge metadata
string, grid names with line breaks... With --nimbus, files written by `nimbus generate` and
`nimbus noise` are added; those carry nimbus's CRC seal, so every damaged copy of them must be
refused.

A damage is then applied on top of each base file: none, 16 garbled bytes at a random offset,
one flipped byte, truncation to 0-7 bytes or to a random length, a corrupt length field in the
metadata (u32 string or value sizes) or corrupt grid offsets (the descriptor's int64s).

Deterministic for a seed: the header UUID pyopenvdb writes at random is replaced by one derived
from the seed and the kind, and every choice comes from random.Random(seed). File i pairs kind
i mod K with damage (i div K) mod D, so N >= K*D covers every pair.

OUTDIR/manifest.tsv lists every file: name, kind, damage, sealed (1 for nimbus's files),
expect (ok: an intact well-formed fog volume that must be read; any: anything but a crash;
refused: must be refused with exit 1), and what was done.
"""
import argparse
import hashlib
import math
import os
import random
import struct
import subprocess
import sys
import tempfile

try:
    import pyopenvdb as vdb
except ImportError:  # pragma: no cover
    sys.stderr.write("make_hostile_vdbs.py: pyopenvdb is not importable (install python3-openvdb; run with /usr/bin/python3)\n")
    sys.exit(2)

UUID_AT, UUID_LEN = 21, 36  # magic (8), file version, library major, minor (4 each), offsets flag (1)

# ---------------------------------------------------------------------------------------------
# Base files written by pyopenvdb


def fog(name="density", cls=vdb.GridClass.FOG_VOLUME):
    g = vdb.FloatGrid()
    g.name = name
    g.gridClass = cls
    return g


def blob(g, rng, n=64, lo=0.0, hi=1.0, extent=8):
    a = g.getAccessor()
    for _ in range(n):
        c = (rng.randrange(extent), rng.randrange(extent), rng.randrange(extent))
        a.setValueOn(c, rng.uniform(lo, hi))
    return g


UNIQUE_SCALE = 0.123456789012345  # doubles that appear only in the transform (patched below)
UNIQUE_SHIFT = 12345.6789012345


def k_fog_small(rng):
    g = blob(fog(), rng)
    g.transform = vdb.createLinearTransform(0.25)
    return [g], {"creator": "fuzz"}


def k_fog_dense(rng):  # a full 16^3 block with Houdini-like values above 1 (up to 5.7)
    g = fog()
    g.fill((0, 0, 0), (15, 15, 15), 1.0)
    blob(g, rng, 200, 0.0, 5.7, 16)
    g.transform = vdb.createLinearTransform(0.1)
    return [g], {}


def k_fog_half(rng):
    g = blob(fog(), rng, 100)
    g.saveFloatAsHalf = True
    return [g], {}


def k_multi_grid(rng):  # density, temperature, a velocity field, a mask
    d = blob(fog(), rng)
    t = blob(fog("temperature"), rng, 32, 200, 900)
    v = vdb.Vec3SGrid()
    v.name = "vel"
    v.getAccessor().setValueOn((1, 1, 1), (1.0, -2.0, 3.0))
    m = vdb.BoolGrid()
    m.name = "mask"
    m.getAccessor().setValueOn((2, 2, 2), True)
    return [d, t, v, m], {"frame": 7, "up_axis": "y", "fps": 24.0}


def k_no_density_name(rng):  # float grids, none named density (the first one is used)
    return [blob(fog("smoke"), rng), blob(fog("fire"), rng)], {}


def k_level_set(rng):
    g = vdb.createLevelSetSphere(1.0, (0.0, 0.0, 0.0), 0.1, 3.0)
    g.name = "surface"
    return [g], {}


def k_level_set_named_density(rng):  # a signed distance field posing as density
    g = vdb.createLevelSetSphere(0.5, (0.2, 0.0, 0.0), 0.05, 3.0)
    g.name = "density"
    return [g], {}


def k_negative(rng):
    return [blob(fog(), rng, 64, -5.0, -0.001)], {}


def k_nan_inf(rng):
    g = blob(fog(), rng)
    a = g.getAccessor()
    a.setValueOn((0, 0, 0), float("nan"))
    a.setValueOn((1, 0, 0), float("inf"))
    a.setValueOn((2, 0, 0), float("-inf"))
    return [g], {}


def k_nan_background(rng):
    g = vdb.FloatGrid(float("nan"))
    g.name = "density"
    blob(g, rng, 16)
    return [g], {}


def k_vec3_only(rng):
    g = vdb.Vec3SGrid()
    g.name = "density"  # the expected name, the wrong type
    a = g.getAccessor()
    for i in range(20):
        a.setValueOn((i, 0, 0), (rng.random(), rng.random(), rng.random()))
    return [g], {}


def k_bool_only(rng):
    g = vdb.BoolGrid()
    g.name = "mask"
    a = g.getAccessor()
    for i in range(20):
        a.setValueOn((i, i, 0), True)
    return [g], {}


def k_int_only(rng):  # pyopenvdb has no Int32Grid: a float grid whose type names are patched
    g = blob(fog("density"), rng)
    return [g], {"_patch_types": True}


def k_empty_grid(rng):
    return [fog()], {}


def k_no_grids(rng):
    return [], {"creator": "fuzz", "note": "no grids at all"}


def k_extent_overflow(rng):  # int32 extent overflow: max - min + 1 does not fit in 32 bits
    g = fog()
    a = g.getAccessor()
    a.setValueOn((vdb.COORD_MIN[0] + 1, 0, 0), 0.5)
    a.setValueOn((vdb.COORD_MAX[0] - 1, 0, 0), 0.5)
    return [g], {}


def k_extent_overflow_xyz(rng):
    g = fog()
    a = g.getAccessor()
    a.setValueOn((vdb.COORD_MIN[0] + 1, vdb.COORD_MIN[1] + 1, vdb.COORD_MIN[2] + 1), 0.5)
    a.setValueOn((vdb.COORD_MAX[0] - 1, vdb.COORD_MAX[1] - 1, vdb.COORD_MAX[2] - 1), 0.5)
    return [g], {}


def k_huge_sparse(rng):  # two voxels 1e6 apart on every axis: a 1e18-voxel box
    g = fog()
    a = g.getAccessor()
    a.setValueOn((0, 0, 0), 0.5)
    a.setValueOn((1000000, 1000000, 1000000), 0.5)
    return [g], {}


def k_sparse_3gb(rng):  # a box of 2048 x 2048 x 200 voxels: 3.4 GB of floats, near the limit
    g = fog()
    a = g.getAccessor()
    a.setValueOn((0, 0, 0), 0.5)
    a.setValueOn((2047, 2047, 199), 0.5)
    return [g], {}


def k_far_away(rng):  # a small cloud near the int32 edge
    g = fog()
    a = g.getAccessor()
    base = vdb.COORD_MAX[0] - 20
    for i in range(8):
        a.setValueOn((base + i, base, base), 0.5)
    return [g], {}


def k_huge_metadata(rng):  # a 3 MB file-metadata string and a 256 KB grid metadata string
    g = blob(fog(), rng)
    g["note"] = "g" * (256 << 10)
    return [g], {"comment": "m" * (3 << 20)}


def k_odd_names(rng):  # names with a line break, a tab and nothing at all
    a = blob(fog("two\nlines"), rng, 8)
    b = vdb.Vec3SGrid()
    b.name = "tab\there"
    b.getAccessor().setValueOn((0, 0, 0), (1, 1, 1))
    c = blob(fog(""), rng, 8)
    return [a, b, c], {"line\nbreak": "value\nwith\nbreaks"}


def k_odd_names_nonfloat(rng):  # no float grid: the message lists names holding line breaks
    b = vdb.Vec3SGrid()
    b.name = "vel\nocity"
    b.getAccessor().setValueOn((0, 0, 0), (1, 1, 1))
    return [b], {}


def k_many_grids(rng):
    return [blob(fog("g%03d" % i), rng, 4) for i in range(60)], {}


def k_negative_scale(rng):
    g = blob(fog(), rng)
    g.transform = vdb.createLinearTransform(-0.1)
    return [g], {}


def k_nonuniform(rng):
    g = blob(fog(), rng)
    g.transform = vdb.createLinearTransform([[0.1, 0, 0, 0], [0, 2.0, 0, 0], [0, 0, 0.001, 0], [0, 0, 0, 1]])
    return [g], {}


def k_sheared(rng):
    g = blob(fog(), rng)
    g.transform = vdb.createLinearTransform([[0.1, 0.3, 0, 0], [0, 0.1, 0.2, 0], [0.05, 0, 0.1, 0], [1e6, -1e6, 3e5, 1]])
    return [g], {}


def k_huge_translation(rng):
    g = blob(fog(), rng)
    g.transform = vdb.createLinearTransform([[1e-3, 0, 0, 0], [0, 1e-3, 0, 0], [0, 0, 1e-3, 0], [UNIQUE_SHIFT, -UNIQUE_SHIFT, UNIQUE_SHIFT, 1]])
    return [g], {"_patch": (UNIQUE_SHIFT, 1e300)}  # too far for pyopenvdb to accept


def k_frustum(rng):
    g = blob(fog(), rng, 64, 0.0, 1.0, 16)
    g.transform = vdb.createFrustumTransform((0, 0, 0), (16, 16, 16), 0.5, 10.0, 0.1)
    return [g], {}


def k_scale_patched(rng, value):  # the stored scale and voxel size replaced after writing
    g = blob(fog(), rng)
    g.transform = vdb.createLinearTransform(UNIQUE_SCALE)
    return [g], {"_patch": (UNIQUE_SCALE, value)}


KINDS = {
    # name: (builder, expect when intact: ok = must be read, any = must not crash)
    "fog_small": (k_fog_small, "ok"),
    "fog_dense": (k_fog_dense, "ok"),
    "fog_half": (k_fog_half, "ok"),
    "multi_grid": (k_multi_grid, "ok"),
    "no_density_name": (k_no_density_name, "ok"),
    "level_set": (k_level_set, "any"),
    "level_set_named_density": (k_level_set_named_density, "any"),
    "negative": (k_negative, "any"),
    "nan_inf": (k_nan_inf, "any"),
    "nan_background": (k_nan_background, "any"),
    "vec3_only": (k_vec3_only, "any"),
    "bool_only": (k_bool_only, "any"),
    "int_only": (k_int_only, "any"),
    "empty_grid": (k_empty_grid, "any"),
    "no_grids": (k_no_grids, "any"),
    "extent_overflow": (k_extent_overflow, "any"),
    "extent_overflow_xyz": (k_extent_overflow_xyz, "any"),
    "huge_sparse": (k_huge_sparse, "any"),
    "sparse_3gb": (k_sparse_3gb, "any"),
    "far_away": (k_far_away, "any"),
    "huge_metadata": (k_huge_metadata, "any"),
    "odd_names": (k_odd_names, "any"),
    "odd_names_nonfloat": (k_odd_names_nonfloat, "any"),
    "many_grids": (k_many_grids, "ok"),
    "negative_scale": (k_negative_scale, "any"),
    "nonuniform_scale": (k_nonuniform, "any"),
    "sheared": (k_sheared, "any"),
    "huge_translation": (k_huge_translation, "any"),
    "tiny_voxels": (lambda r: k_scale_patched(r, 1e-300), "any"),
    "huge_voxels": (lambda r: k_scale_patched(r, 1e300), "any"),
    "frustum": (k_frustum, "any"),
    "zero_scale": (lambda r: k_scale_patched(r, 0.0), "any"),
    "nan_scale": (lambda r: k_scale_patched(r, float("nan")), "any"),
    "inf_scale": (lambda r: k_scale_patched(r, float("inf")), "any"),
    "subnormal_scale": (lambda r: k_scale_patched(r, 5e-324), "any"),
}

NIMBUS_KINDS = {
    "nimbus_steam": ["generate", "--preset", "steam", "--voxel-size", "0.02"],
    "nimbus_steam_float": ["generate", "--preset", "steam", "--voxel-size", "0.04", "--float"],
    "nimbus_noise": ["noise", "--kind", "gradient", "--res", "24"],
}

DAMAGES = ["none", "garble16", "flip1", "trunc_tiny", "trunc", "metalen", "offsets"]


def fixed_uuid(seed, kind):
    h = hashlib.sha256(("%d/%s" % (seed, kind)).encode()).hexdigest()
    return "%s-%s-%s-%s-%s" % (h[0:8], h[8:12], h[12:16], h[16:20], h[20:32])


def write_pyopenvdb(kind, seed, tmpdir):
    builder, _ = KINDS[kind]
    rng = random.Random("%d/%s" % (seed, kind))
    grids, meta = builder(rng)
    patch_types = meta.pop("_patch_types", False)
    patch = meta.pop("_patch", None)
    path = os.path.join(tmpdir, kind + ".vdb")
    vdb.write(path, grids, metadata=meta or None)
    with open(path, "rb") as f:
        data = bytearray(f.read())
    os.unlink(path)
    if data[UUID_AT - 1] == 1 and data[UUID_AT + 8:UUID_AT + 9] == b"-":  # has offsets, then the UUID text
        data[UUID_AT:UUID_AT + UUID_LEN] = fixed_uuid(seed, kind).encode()
    if patch_types:  # "float" and "int32" have the same length, and both values 4 bytes
        data = bytearray(bytes(data).replace(b"Tree_float_5_4_3", b"Tree_int32_5_4_3"))
    if patch is not None:  # every stored copy of a double replaced (pyopenvdb refuses the value)
        old, new = struct.pack("<d", patch[0]), struct.pack("<d", patch[1])
        assert old in data, kind
        data = bytearray(bytes(data).replace(old, new))
    return bytes(data)


def write_nimbus(kind, nimbus, tmpdir):
    path = os.path.join(tmpdir, kind + ".vdb")
    r = subprocess.run([nimbus] + NIMBUS_KINDS[kind] + ["-o", path], stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise SystemExit("make_hostile_vdbs.py: %s failed (%d): %s" % (kind, r.returncode, r.stderr.strip()))
    with open(path, "rb") as f:
        data = f.read()
    os.unlink(path)
    return data


# ---------------------------------------------------------------------------------------------
# Damage


def string_length_fields(data, limit=1 << 16):
    """Offsets of u32 fields that hold the length of the printable string after them (metadata
    keys and type names, grid names and types, map type names)."""
    out = []
    end = min(len(data), limit)
    for o in range(UUID_AT + UUID_LEN, end - 5):
        n = struct.unpack_from("<I", data, o)[0]
        if 3 <= n <= 64 and o + 4 + n <= len(data):
            s = data[o + 4:o + 4 + n]
            if all(32 <= c < 127 for c in s) and any(65 <= c <= 122 for c in s):
                out.append(o)
    return out


def metadata_fields(data):
    """The file metadata's length fields, walked as MetaMap::writeMeta stores them: u32 count,
    then per entry u32 + key, u32 + type name, u32 + value."""
    out = []
    o = UUID_AT + UUID_LEN
    if len(data) < o + 4:
        return out
    out.append(o)
    count = struct.unpack_from("<I", data, o)[0]
    o += 4
    for _ in range(min(count, 1000)):
        for _part in range(3):
            if o + 4 > len(data):
                return out
            n = struct.unpack_from("<I", data, o)[0]
            out.append(o)
            o += 4 + n
    return out


def descriptor_offsets(data):
    """Offsets of the int64 grid, block and end positions of each grid descriptor: after the
    grid type string ("Tree_...") and the instance parent name (usually empty)."""
    out = []
    start = 0
    while True:
        at = data.find(b"Tree_", start)
        if at < 4:
            break
        start = at + 1
        n = struct.unpack_from("<I", data, at - 4)[0]
        o = at + n
        if n > 64 or o + 4 > len(data):
            continue
        parent = struct.unpack_from("<I", data, o)[0]
        o += 4 + parent
        if parent <= 256 and o + 24 <= len(data):
            gp, bp, ep = struct.unpack_from("<qqq", data, o)
            if 0 < gp <= bp <= ep <= len(data):
                out.extend([o, o + 8, o + 16])
    return out


BIG_U32 = [0xFFFFFFFF, 0xB2D05E00, 0x7FFFFFFF, 0x80000000, 0x10000000, 0x00100000]


def damage(data, how, rng):
    """Returns (bytes, description)."""
    n = len(data)
    if how == "none":
        return data, "intact, %d bytes" % n
    if how == "garble16":
        at = rng.randrange(max(1, n - 16))
        junk = bytes(rng.randrange(256) for _ in range(min(16, n - at)))
        if junk == data[at:at + len(junk)]:
            junk = bytes((b ^ 0xFF) for b in junk)
        return data[:at] + junk + data[at + len(junk):], "16 garbled bytes at %d of %d" % (at, n)
    if how == "flip1":
        at = rng.randrange(n)
        x = rng.randrange(1, 256)
        return data[:at] + bytes([data[at] ^ x]) + data[at + 1:], "byte %d of %d xor 0x%02x" % (at, n, x)
    if how == "trunc_tiny":
        k = rng.randrange(8)
        return data[:k], "truncated to %d of %d bytes" % (k, n)
    if how == "trunc":
        k = rng.randrange(8, n)
        return data[:k], "truncated to %d of %d bytes" % (k, n)
    if how == "metalen":
        fields = metadata_fields(data)
        if rng.random() < 0.5 or not fields:
            fields = string_length_fields(data) or fields
        o = rng.choice(fields)
        old = struct.unpack_from("<I", data, o)[0]
        new = rng.choice(BIG_U32 + [old + 1, old * 1000 + 7, max(0, old - 1)])
        if new == old:
            new = 0xFFFFFFFF
        return data[:o] + struct.pack("<I", new & 0xFFFFFFFF) + data[o + 4:], \
            "u32 length at %d: %d -> %d" % (o, old, new & 0xFFFFFFFF)
    if how == "offsets":
        fields = descriptor_offsets(data)
        if not fields:
            return damage(data, "metalen", rng)
        o = rng.choice(fields)
        old = struct.unpack_from("<q", data, o)[0]
        new = rng.choice([-1, 0, old + 1, old - 1, n, n + 1, 1 << 40, -(1 << 62), (1 << 63) - 1, old // 2])
        if new == old:
            new = -1
        return data[:o] + struct.pack("<q", new) + data[o + 8:], "int64 offset at %d: %d -> %d" % (o, old, new)
    raise ValueError(how)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--count", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--nimbus", help="the nimbus program: also damage files it writes (sealed)")
    ap.add_argument("--kinds", help="comma-separated subset of the base kinds")
    ap.add_argument("--damages", help="comma-separated subset of " + ",".join(DAMAGES))
    ap.add_argument("--list", action="store_true", help="print the kinds and damages and exit")
    a = ap.parse_args()

    kinds = list(KINDS) + (list(NIMBUS_KINDS) if a.nimbus else [])
    if a.list:
        print("kinds:", " ".join(list(KINDS) + list(NIMBUS_KINDS)))
        print("damages:", " ".join(DAMAGES))
        return 0
    if a.kinds:
        kinds = [k for k in a.kinds.split(",") if k]
        bad = [k for k in kinds if k not in KINDS and k not in NIMBUS_KINDS]
        if bad or (any(k in NIMBUS_KINDS for k in kinds) and not a.nimbus):
            ap.error("--kinds: unknown or needs --nimbus: %s" % ",".join(bad or kinds))
    damages = DAMAGES
    if a.damages:
        damages = [d for d in a.damages.split(",") if d]
        if any(d not in DAMAGES for d in damages):
            ap.error("--damages: one of " + ",".join(DAMAGES))
    if a.count < 1:
        ap.error("--count must be >= 1")
    os.makedirs(a.outdir, exist_ok=True)

    base = {}
    with tempfile.TemporaryDirectory() as tmp:
        for k in kinds:
            base[k] = write_nimbus(k, a.nimbus, tmp) if k in NIMBUS_KINDS else write_pyopenvdb(k, a.seed, tmp)

    rng = random.Random(a.seed)
    rows = []
    for i in range(a.count):
        kind = kinds[i % len(kinds)]
        how = damages[(i // len(kinds)) % len(damages)]
        data, what = damage(base[kind], how, rng)
        sealed = kind in NIMBUS_KINDS
        if how == "none":
            expect = "ok" if sealed else KINDS[kind][1]
        else:
            expect = "refused" if sealed else "any"
        name = "%04d-%s-%s.vdb" % (i, kind, how)
        with open(os.path.join(a.outdir, name), "wb") as f:
            f.write(data)
        rows.append((name, kind, how, "1" if sealed else "0", expect, what))
    with open(os.path.join(a.outdir, "manifest.tsv"), "w") as f:
        f.write("file\tkind\tdamage\tsealed\texpect\twhat\n")
        for r in rows:
            f.write("\t".join(r) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
