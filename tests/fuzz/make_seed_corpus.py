#!/usr/bin/python3
"""Writes the fuzz seed corpus kept in the repository (tests/fuzz/corpus/):

    make_seed_corpus.py --nimbus BIN [--out tests/fuzz/corpus]

  params_json/  inputs of fuzz_params.cpp: "[preset:NAME\\n]PARAMS[\\0SET...]" (see there): whole
                preset documents, "cloud" overrides, --set arguments, and files that must be
                refused cleanly;
  vdb/          inputs of fuzz_vdb.cpp: small intact files from pyopenvdb (make_hostile_vdbs.py's
                kinds) and from nimbus (sealed), and damaged copies that must be refused cleanly.

Deterministic (the generator's seeds are fixed), so rerunning it rewrites the same bytes; inputs the
fuzzer found and that now pass (e.g. vdb/nodes-without-active-voxels.vdb) are kept beside them. Every
file here must pass the replay (Fuzz.*CorpusReplay); inputs that break the code go to
tests/fuzz/findings/ instead.
"""
import argparse
import json
import os
import random
import subprocess
import sys
import tempfile

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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nimbus", required=True)
    ap.add_argument("--out", default=os.path.join(HERE, "corpus"))
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for sub, seeds in [("params_json", params_seeds()), ("vdb", vdb_seeds(a.nimbus, tmp))]:
            d = os.path.join(a.out, sub)
            os.makedirs(d, exist_ok=True)
            for name, data in sorted(seeds.items()):
                with open(os.path.join(d, name), "wb") as f:
                    f.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
