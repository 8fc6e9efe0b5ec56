#!/usr/bin/python3
"""Fuzz.HostileViewerAndFarmFiles: runs the nimbus program on mutated viewer scripts, sky files,
view states and farm job descriptions, and checks the command-line contract (docs/reliability.md)
on every run. Viewer scripts (samples/viewer/view_script.cpp) and farm jobs (samples/cli/farm_job.cpp)
are parsed in samples/, which no harness may compile: the program is their only way in.

From seed documents (docs/viewer.md's script, sky and state; the default sky; a frames and a bricks
job.json as `nimbus farm slurm` writes them), case i makes one mutated document: kind i mod 4
(script, sky, state, job) and mutation (i div 4) mod M of that kind's M (so 4 x M cases cover every
pair), every choice drawn from random.Random("SEED/i"): the same case for a seed, whatever --count.
Mutations: keys deleted, duplicated or added, values of the wrong type or null, extreme numbers
(1e308, -1e308, 1e-320, -0, 1e309, NaN, 2^64...), 100 kB strings (and a file over the 16 MiB
limit), control characters and ANSI escapes, bytes that are not UTF-8, nesting within the 64-level
limit and beyond it, truncation, garbled bytes, and file names in the document (a script's record
and save_sky, a sky's cloud files, a job's outputs and folders) set to printf patterns
("%s%s%s%n", "%99999999d", "x%0s.vdb", "a%099d.vdb"), /dev/zero, a FIFO, a folder or the input
itself; for jobs also frame ranges ([1, 2000000000], 10^6 tasks...), chunk 0, unknown kinds, brick
layouts, and hostile task logs (`--array-job`; 6 tasks, one log each: /dev/zero, a 2.5 GiB sparse
file without a line break, a 4 MB line, escape sequences, a folder, a plain log; an escape sequence
in the job folder's name; apart, a log that is a FIFO).

Each case runs in its own folder (its working directory), holding the input, tiny.json (a one-frame
script), plume.0001.vdb (the file cloud of docs/viewer.md's sky), a FIFO, a subfolder and, for
jobs, damaged outputs and task logs:
  script  nimbus --check-only view --headless --script F
  sky     nimbus --check-only view --headless --script tiny.json --sky F
  state   nimbus --check-only render --view-state F -o DIR/out.exr
          nimbus --check-only view --headless --script tiny.json --state F
  job     nimbus farm check DIR [--array-job 7]         (F = DIR/job.json)

The contract checked on every run:
  - no signal (a crash, an abort, SIGXCPU from --cpu-s, the kill at --timeout), exit 0, 1 or 2;
  - peak resident memory at most --rss-mb (wait4's ru_maxrss), under an address-space limit
    (--mem-mb, RLIMIT_AS, soft) so that a runaway allocation fails inside the process;
  - on exit 1 or 2: stdout empty and stderr exactly one line that names the input (its path, the
    flag that gave it, or the bad file name it holds by its key: "script record '...'", "sky cloud
    file '...'"); except that `farm check` reports failed tasks on stdout with exit 1 and
    nothing on stderr, a normal outcome;
  - no stderr line over 1100 characters; no control character (bytes below 0x20 but the line
    breaks, and 0x7f) in stderr, nor in farm check's stdout (it echoes paths read from the job);
  - an intact seed (mutation "none") is accepted: exit 0 (farm check: its report, exit 0 or 1);
  - the case's folder is unchanged (every entry below it: names, kinds, sizes, inodes, mtimes, as
    tests/support/hostile_table.cpp's snapshot(), which leaves out the folder itself):
    --check-only and farm check write nothing, not even a probe file made and removed in a
    subfolder (a subfolder whose mtime alone changed is reported as such).

    run_hostile_json.py --nimbus BIN [--count 240] [--seed 1] [--jobs 2] [--mem-mb 4096] [--rss-mb 2048]
                        [--cpu-s 30] [--timeout 20] [--workdir DIR] [--keep] [--report FILE.md]
                        [--kinds script,sky,state,job] [--mutations a,b] [--case N] [--list]

Prints the counts overall, per kind and per mutation (as Markdown tables, also to --report) and
every violation with its command, working directory and the input kept in the work folder; exits 1
when any run broke the contract. Case folders of runs that kept it are removed unless --keep.
"""
import argparse
import collections
import concurrent.futures
import json
import os
import random
import resource
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from program_runs import limits, outcome  # noqa: E402
ROOT = os.path.dirname(os.path.dirname(HERE))
KINDS = ("script", "sky", "state", "job")
MAX_STDERR_LINE = 1100
HUGE = 100 * 1024          # a "huge" string: 100 kB
OVER_LIMIT = (16 << 20) + 4096  # a file over nimbus's 16 MiB limit on JSON inputs

# ---------------------------------------------------------------------------------------------
# JSON text, including what json.dumps cannot write: duplicate keys, raw tokens, raw bytes


class Raw:
    """Bytes written as they are: a number json.dumps would not write, a string that is not UTF-8."""

    def __init__(self, text):
        self.text = text if isinstance(text, bytes) else text.encode()


class Pairs:
    """An object written member by member, so that a key may appear twice."""

    def __init__(self, items):
        self.items = list(items)


def dump(v):
    if isinstance(v, Raw):
        return v.text
    if isinstance(v, (dict, Pairs)):
        items = v.items if isinstance(v, Pairs) else list(v.items())
        return b"{" + b", ".join(dump(k) + b": " + dump(x) for k, x in items) + b"}"
    if isinstance(v, list):
        return b"[" + b", ".join(dump(x) for x in v) + b"]"
    return json.dumps(v, ensure_ascii=False).encode("utf-8")


def copy(doc):
    return json.loads(json.dumps(doc))


def locations(doc, prefix=()):
    """The path (keys and indices) of every value below the root."""
    out = []
    items = doc.items() if isinstance(doc, dict) else enumerate(doc) if isinstance(doc, list) else ()
    for k, v in items:
        out.append(prefix + (k,))
        out.extend(locations(v, prefix + (k,)))
    return out


def get(doc, path):
    for k in path:
        doc = doc[k]
    return doc


def put(doc, path, value):
    """doc with the value at path replaced (the root when path is empty)."""
    if not path:
        return value
    get(doc, path[:-1])[path[-1]] = value
    return doc


def show(path):
    text = ""
    for k in path:
        text += "[%d]" % k if isinstance(k, int) else ("." if text else "") + str(k)[:40]
    return text or "(root)"


# ---------------------------------------------------------------------------------------------
# Seeds: documents the program accepts


DOCS_SKY = {
    "clouds": [
        {"preset": "cumulus-mediocris", "position": [0, 0, 0], "seed": 1},
        {"preset": "cumulus-humilis", "position": [1500, -1200, 0], "seed": 3, "overrides": {"coverage": 0.5}},
        {"file": "plume.%04d.vdb", "grid": "density", "up": "auto", "position": [0, 0, 0]},
    ],
    "wind": [6.0, 2.5, 0.0],
    "evolution": 3.0,
    "sun": {"elevation": 35.0, "azimuth": 135.0},
    "voxel_size": 30.0,
    "keyframe_interval": 30.0,
}


def default_sky():
    with open(os.path.join(ROOT, "volume", "skies", "default.json")) as f:
        return json.load(f)


def state_of(sky):
    return {
        "nimbus": "view state", "sky": sky, "scene": "sky",
        "camera": {"eye": [-600.0, 250.0, 5200.0], "look_at": [400.0, 1500.0, -1500.0], "fov": 60.0},
        "time": {"sky": 120.0, "evolution": 120.0, "speed": 10.0, "paused": False},
        "optics": {"extinction": 0.04, "albedo": [0.99, 0.99, 0.99], "phase": "dual:0.7,-0.25,0.8", "multiple": 2,
                   "ms_method": "light-volume", "ms_grid": 48, "ms_photons": 524288},
        "renderer": {"slices": 128, "light_res": 256, "cloud_shadow_res": 256, "render_scale": 1.0,
                     "exposure": 0.0, "jitter": True, "shafts": "raymarch:24"},
    }


def seeds(kind, ctx):
    """name -> document: what the mutations start from."""
    if kind == "script":
        return {
            "docs": {"size": [640, 360], "frames": 120, "dt": 0.0333, "screenshot_every": 10, "adaptive": False,
                     "record": "frames.json",
                     "camera": [{"frame": 0, "eye": [-600, 250, 5200], "look_at": [400, 1500, -1500]},
                                {"frame": 119, "eye": [1500, 600, 3000], "look_at": [400, 1500, -1500]}],
                     "events": [{"frame": 30, "key": "space"}, {"frame": 40, "drag": [50, 0], "button": "left"},
                                {"frame": 50, "scroll": 2}, {"frame": 60, "sun": [12, 250]}, {"frame": 70, "key": "f12"},
                                {"frame": 80, "save_sky": "saved-sky.json"}]},
            "small": {"size": [64, 36], "frames": 3, "dt": 0.1, "screenshot_every": 2},
        }
    if kind == "sky":
        return {"default": default_sky(), "docs": copy(DOCS_SKY)}
    if kind == "state":
        return {"default": state_of(default_sky()), "docs": state_of(copy(DOCS_SKY))}
    common = {"nimbus": "farm job", "program": ctx["nimbus"], "workdir": ctx["dir"], "dir": ctx["jobdir"]}
    return {
        "frames": dict(common, kind="frames", chunk=2, frames=[1, 4], output="out/sky.%04d.exr",
                       preview="out/sky.%04d.png",
                       command=["render", "--preset", "cumulus-congestus", "--frames", "1-4", "-o", "out/sky.%04d.exr",
                                "--preview", "out/sky.%04d.png"]),
        "bricks": dict(common, kind="bricks", chunk=1, bricks="2x2x1", merge_output="field.vdb",
                       command=["generate", "--preset", "cumulus-field", "--voxel-size", "12", "-o", "field.vdb"]),
    }


# ---------------------------------------------------------------------------------------------
# Mutations: each takes (doc, rng, ctx) and returns (document or bytes, what was done)

NUMBERS = ["1e308", "-1e308", "1e-320", "0", "-0", "-0.0", "1e309", "-1e309", "NaN", "Infinity", "-Infinity",
           "18446744073709551616", "-9223372036854775809", "9223372036854775807", "4294967296", "2147483648",
           "-2147483649", "5e-324", "1.0000000000000002", "0.1", "100000", "100001", "1e15", "10000000", "-1",
           "1E400", "0x10", "01", "1.", "+1", ".5"]
OTHER_VALUES = ["text", 1, 2.5, True, False, [], {}, [1, 2, 3], {"a": 1}, [0, 0, 0], ""]
CONTROL_TEXTS = ["\x1b[31mred\x1b[0m", "a\nb", "a\rb", "nul\x00byte", "\x07bell", "back\x08\x08", "\u009b31m",
                 "line\u2028sep", "del\x7f", "\x1b]0;title\x07", "tab\there"]
RAW_CONTROL = [b'"\x1b[31mraw"', b'"raw\nline"', b'"\x00"', b'"\r"']
BAD_UTF8 = [b"\xff\xfe", b"\xc3\x28", b"\xed\xa0\x80", b"\xf4\x90\x80\x80", b"\xc0\xaf", b"\x80", b"abc\xe2\x82"]
ODD_KEYS = ["x", "", "\x1b[2J\x1b[H", "%s%n", "__proto__", "clouds ", "Clouds", "a" * 5000, "\u00e9t\u00e9", "0"]
PRINTF_PATHS = ["%s%s%s%n", "%99999999d", "x%0s.vdb", "a%099d.vdb", "%n.vdb", "%04d%04d.vdb", "%d%d.json",
                "%2147483648d.vdb", "%-5d.vdb", "%%.vdb"]


def path_values(ctx):
    return PRINTF_PATHS + ["/dev/zero", ctx["fifo"], "fifo", ctx["sub"], "sub", "sub/", ctx["self"], "", "/", ".", "..",
                           "/proc/self/mem", "/dev/full", "/dev/stdout", "no/such/dir/x.json", "x" * 5000 + ".json",
                           "a\nb.json", "\x1b[31mred.json", os.path.join(ctx["dir"], "out.exr"), "tiny.json",
                           "sub/x.json", "sub/new/x.json"]


def pick_location(doc, rng, want=None):
    locs = [p for p in locations(doc) if want is None or want(get(doc, p))]
    return rng.choice(locs) if locs else None


def m_none(doc, rng, ctx):
    return doc, "intact"


def m_delete_key(doc, rng, ctx):
    p = pick_location(doc, rng)
    if p is None or not isinstance(get(doc, p[:-1]), dict):
        dict_locs = [q for q in locations(doc) if isinstance(get(doc, q[:-1]), dict)]
        p = rng.choice(dict_locs)
    del get(doc, p[:-1])[p[-1]]
    return doc, "deleted " + show(p)


def m_duplicate_key(doc, rng, ctx):
    objects = [()] + [p for p in locations(doc) if isinstance(get(doc, p), dict) and get(doc, p)]
    p = rng.choice(objects)
    o = get(doc, p)
    k = rng.choice(list(o))
    second = rng.choice([o[k], rng.choice(OTHER_VALUES), None])
    items = list(o.items())
    at = rng.randrange(len(items) + 1)
    items.insert(at, (k, second))
    return put(doc, p, Pairs(items)), "duplicated %s.%s (second value %s)" % (show(p), k, json.dumps(second)[:40])


def m_wrong_type(doc, rng, ctx):
    p = pick_location(doc, rng)
    old = get(doc, p)
    value = rng.choice([v for v in OTHER_VALUES if type(v) is not type(old)])
    return put(doc, p, value), "%s: %s instead of %s" % (show(p), json.dumps(value), type(old).__name__)


def m_null(doc, rng, ctx):
    p = pick_location(doc, rng) if rng.random() < 0.9 else ()
    return put(doc, p, None), "%s: null" % show(p)


def m_number(doc, rng, ctx):
    p = pick_location(doc, rng, lambda v: isinstance(v, (int, float)) and not isinstance(v, bool)) or \
        pick_location(doc, rng)
    token = rng.choice(NUMBERS)
    return put(doc, p, Raw(token)), "%s: %s" % (show(p), token)


def m_huge_string(doc, rng, ctx):
    if rng.random() < 0.1:  # the whole file over the 16 MiB limit
        doc["description"] = "x" * OVER_LIMIT
        return doc, "a 16 MiB + 4 KiB description (the file over the limit)"
    text = rng.choice(["x", "\u00e9", "%s", "\x1b[31m", "\n"]) * (HUGE // 2) + "end"
    if rng.random() < 0.3 and isinstance(doc, dict):
        doc[text] = 1
        return doc, "a key of %d characters" % len(text)
    p = pick_location(doc, rng, lambda v: isinstance(v, str)) or pick_location(doc, rng)
    return put(doc, p, text), "%s: a string of %d characters" % (show(p), len(text))


def m_control_chars(doc, rng, ctx):
    p = pick_location(doc, rng, lambda v: isinstance(v, str)) or pick_location(doc, rng)
    r = rng.random()
    if r < 0.2:
        raw = rng.choice(RAW_CONTROL)
        return put(doc, p, Raw(raw)), "%s: unescaped control bytes %r (not JSON)" % (show(p), raw)
    text = rng.choice(CONTROL_TEXTS)
    if r < 0.5 and isinstance(get(doc, p[:-1]), dict):  # in a key
        parent = get(doc, p[:-1])
        parent[p[-1] + text] = parent.pop(p[-1])
        return doc, "key %s + %r" % (show(p), text)
    return put(doc, p, text), "%s: %r" % (show(p), text)


def m_non_utf8(doc, rng, ctx):
    p = pick_location(doc, rng, lambda v: isinstance(v, str)) or pick_location(doc, rng)
    bad = rng.choice(BAD_UTF8)
    old = get(doc, p)
    base = old.encode("utf-8", "replace")[:20] if isinstance(old, str) else b"v"
    if rng.random() < 0.3 and isinstance(get(doc, p[:-1]), dict):
        parent = get(doc, p[:-1])
        items = [(Raw(b'"' + k.encode() + bad + b'"') if k == p[-1] else k, v) for k, v in parent.items()]
        return put(doc, p[:-1], Pairs(items)), "key %s + bytes %r" % (show(p), bad)
    return put(doc, p, Raw(b'"' + base + bad + b'"')), "%s: bytes %r" % (show(p), bad)


def nest(depth, inner, rng):
    if rng.random() < 0.5:
        return Raw(b"[" * depth + dump(inner) + b"]" * depth)
    return Raw(b'{"a": ' * depth + dump(inner) + b"}" * depth)


def m_deep_within(doc, rng, ctx):
    p = pick_location(doc, rng)
    depth = max(1, 64 - len(p) - rng.choice([0, 0, 1, 5, 20]))  # the whole file at most 64 levels deep
    return put(doc, p, nest(depth, rng.choice([1, "x", None]), rng)), "%s: a value %d levels deep (%d in all)" % (
        show(p), depth, len(p) + depth)


def m_deep_beyond(doc, rng, ctx):
    p = pick_location(doc, rng)
    depth = rng.choice([65 - len(p), 66 - len(p), 100, 1000, 100000])
    return put(doc, p, nest(depth, get(doc, p), rng)), "%s nested in %d more levels" % (show(p), depth)


def m_truncate(doc, rng, ctx):
    text = dump(doc)
    n = rng.choice([0, 1, rng.randrange(len(text)), len(text) - 1])
    return text[:n], "cut to %d of %d bytes" % (n, len(text))


def m_garble(doc, rng, ctx):
    text = bytearray(dump(doc))
    spots = sorted(rng.randrange(len(text)) for _ in range(rng.randint(1, 8)))
    for at in spots:
        text[at] = rng.randrange(256)
    return bytes(text), "%d bytes garbled at %s" % (len(spots), ",".join(map(str, spots[:8])))


def m_unknown_key(doc, rng, ctx):
    objects = [()] + [p for p in locations(doc) if isinstance(get(doc, p), dict)]
    p = rng.choice(objects)
    key = rng.choice(ODD_KEYS)
    get(doc, p)[key] = rng.choice(OTHER_VALUES)
    return doc, "added key %r to %s" % (key[:40], show(p))


def m_empty(doc, rng, ctx):
    containers = [()] + [p for p in locations(doc) if isinstance(get(doc, p), (dict, list))]
    p = rng.choice(containers)
    if not p and rng.random() < 0.5:
        value = rng.choice([Raw(b""), Raw(b" \n"), [], "", 0, None])
    else:
        value = type(get(doc, p))()
    return put(doc, p, value), "%s emptied (%s)" % (show(p), dump(value)[:20].decode("utf-8", "replace"))


def m_path(doc, rng, ctx):
    """A file name the document holds, or adds, set to a hostile one."""
    value = rng.choice(path_values(ctx))
    kind = ctx["kind"]
    if kind == "script":
        if rng.random() < 0.5:
            doc["record"] = value
            return doc, "record: %r" % value[:60]
        doc.setdefault("events", []).append({"frame": 0, "save_sky": value})
        return doc, "an event saving the sky to %r" % value[:60]
    sky = doc["sky"] if kind == "state" and isinstance(doc.get("sky"), dict) else doc
    if kind in ("sky", "state"):
        clouds = sky.setdefault("clouds", [])
        cloud = {"file": value}
        if rng.random() < 0.3:
            cloud["grid"] = rng.choice(["density", "\x1b[31m", "a" * 2000, ""])
        if clouds and rng.random() < 0.5:
            clouds[rng.randrange(len(clouds))] = cloud
        else:
            clouds.append(cloud)
        return doc, "a cloud file %r" % value[:60]
    key = rng.choice(["output", "preview", "merge_output", "workdir", "dir", "program", "command"])
    if key == "command":
        cmd = doc.get("command") or ["render"]
        cmd[rng.randrange(len(cmd))] = value
        doc["command"] = cmd
    else:
        doc[key] = value
    return doc, "%s: %r" % (key, value[:60])


COMMON = [m_none, m_delete_key, m_duplicate_key, m_wrong_type, m_null, m_number, m_huge_string, m_control_chars,
          m_non_utf8, m_deep_within, m_deep_beyond, m_truncate, m_garble, m_path, m_unknown_key, m_empty]


# Kind-specific mutations ---------------------------------------------------------------------

def m_script_events(doc, rng, ctx):
    frames = doc.get("frames", 10)
    choices = [
        ("20000 key events", lambda: [{"frame": 0, "key": "space"}] * 20000),
        ("an event past the last frame", lambda: [{"frame": frames, "key": "g"}]),
        ("an event of two kinds", lambda: [{"frame": 0, "key": "g", "scroll": 1}]),
        ("an event without a kind", lambda: [{"frame": 0}]),
        ("an unknown key name", lambda: [{"frame": 0, "key": rng.choice(["ctrl+alt+del", "\x1b[A", "F12", "", "a" * 3000])}]),
        ("a drag of 1e5 pixels and a bad button", lambda: [{"frame": 0, "drag": [1e5, -1e5], "button": "middle"}]),
        ("a sun out of range", lambda: [{"frame": 0, "sun": [91, 360]}]),
        ("a save_sky to the script itself", lambda: [{"frame": 0, "save_sky": ctx["self"]}]),
        ("two save_sky to one file", lambda: [{"frame": 0, "save_sky": "s.json"}, {"frame": 1, "save_sky": "s.json"}]),
        ("save_sky and record to one file", lambda: [{"frame": 0, "save_sky": "frames.json"}]),
        ("a frame of 2^31", lambda: [{"frame": 2147483648, "key": "g"}]),
        ("events as an object", lambda: {"frame": 0, "key": "g"}),
    ]
    if rng.random() < 0.3:
        cams = [("camera keys going back", [{"frame": 5, "eye": [0, 0, 0], "look_at": [1, 0, 0]},
                                             {"frame": 1, "eye": [0, 0, 0], "look_at": [1, 0, 0]}]),
                ("a camera key with eye = look_at", [{"frame": 0, "eye": [1, 2, 3], "look_at": [1, 2, 3]}]),
                ("a camera key at 1e8 m", [{"frame": 0, "eye": [1e8, 0, 0], "look_at": [0, 0, 0]}]),
                ("20000 camera keys", [{"frame": i, "eye": [i, 1, 1], "look_at": [0, 0, 0]} for i in range(20000)]),
                ("a camera key with a fourth member", [{"frame": 0, "eye": [0, 0, 1], "look_at": [0, 0, 0], "x": 1}])]
        what, cam = rng.choice(cams)
        doc["camera"] = cam
        return doc, what
    what, make = rng.choice(choices)
    doc["events"] = make()
    return doc, what


def m_script_values(doc, rng, ctx):
    key, value = rng.choice([("size", [8192, 8192]), ("size", [8193, 16]), ("size", [16]), ("size", [15, 16]),
                             ("frames", 100000), ("frames", 100001), ("frames", 0), ("dt", 60), ("dt", 60.000001),
                             ("dt", -1e-320), ("screenshot_every", 100001), ("screenshot_every", -1),
                             ("adaptive", "yes"), ("record", ""), ("record", 5)])
    doc[key] = value
    return doc, "%s: %s" % (key, json.dumps(value))


def m_sky_clouds(doc, rng, ctx):
    sky = doc["sky"] if ctx["kind"] == "state" else doc
    one = {"preset": "steam", "position": [0, 0, 0], "seed": 1}
    what, clouds = rng.choice([
        ("64 clouds", [dict(one, seed=i) for i in range(64)]),
        ("65 clouds", [dict(one, seed=i) for i in range(65)]),
        ("5000 clouds", [dict(one, seed=i) for i in range(5000)]),
        ("a cloud with a preset and a file", [dict(one, file="a.vdb")]),
        ("a file cloud with overrides", [{"file": "a.vdb", "overrides": {"coverage": 1}}]),
        ("a seed of 2^32", [dict(one, seed=4294967296)]),
        ("a position beyond 1e6 m", [dict(one, position=[1e6 + 1, 0, 0])]),
        ("overrides of an unknown key", [dict(one, overrides={"no_such": 1})]),
        ("overrides of a field's unknown key", [{"preset": "cumulus-field", "overrides": {"field": {"x\n": 1}}}]),
        ("overrides holding the whole preset twice", [dict(one, overrides={"shapes": [{"kind": "ellipsoid"}] * 2000})]),
        ("up: sideways", [{"file": "a.vdb", "up": "x"}]),
        ("a file pattern with two fields", [{"file": "a.%04d.%04d.vdb"}]),
    ])
    sky["clouds"] = clouds
    return doc, what


def m_state_strings(doc, rng, ctx):
    section, key, value = rng.choice([
        ("optics", "phase", "dual:0.7,-0.25,0.8,1"), ("optics", "phase", "hg:1e308"), ("optics", "phase", "dual:nan,nan,nan"),
        ("optics", "phase", "hg:0.5\nsecond line"), ("optics", "phase", "hg:" + "9" * HUGE),
        ("optics", "phase", "dual:" + "0," * 30000 + "0"), ("optics", "phase", "\x1b[31mhg:0.5"),
        ("renderer", "shafts", "raymarch:99999999999999999999"), ("renderer", "shafts", "raymarch:-1"),
        ("renderer", "shafts", "raymarch:" + "1" * HUGE), ("renderer", "shafts", "analytic:table:1e3"),
        ("renderer", "shafts", "raymarch:24\nx"), ("renderer", "shafts", "reference"),
        ("optics", "ms_method", "Octaves"), ("optics", "ms_method", "light-volume\x00"),
        ("optics", "ms_photons", 268435457), ("optics", "ms_photons", -9223372036854775808),
        ("optics", "ms_photons", 1.5), ("renderer", "light_res", 4097), ("renderer", "render_scale", 0.0099),
        ("camera", "fov", 179.0001), ("camera", "eye", [1e308, 0, 0]), ("time", "sky", 1e9 + 1),
        (None, "scene", "sky\n"), (None, "scene", "\x1b[31msky"), (None, "scene", "x" * HUGE), (None, "nimbus", {"deep": [1]}),
    ])
    target = doc if section is None else doc.setdefault(section, {})
    if not isinstance(target, dict):
        target = doc[section] = {}
    target[key] = value
    return doc, "%s: %s" % (key if section is None else section + "." + key, json.dumps(value)[:60])


def m_job_frames(doc, rng, ctx):
    frames, chunk = rng.choice([([1, 2000000000], 1), ([1, 9999999], 10), ([1, 9999999], 1), ([-9999999, 9999999], 1000000),
                                ([1, 1000000], 1), ([5, 1], 1), ([0, 0], 1), ([1], 1), ([1, 2, 3], 1), (["1", "4"], 1),
                                ([1.5, 4], 1), ([None, 4], 1), ({"first": 1}, 1)])
    doc["kind"], doc["frames"], doc["chunk"] = "frames", frames, chunk
    doc.setdefault("output", "out/sky.%04d.exr")
    doc.setdefault("preview", "")
    return doc, "frames %s, chunk %d" % (json.dumps(frames), chunk)


def m_job_chunk(doc, rng, ctx):
    value = rng.choice([0, -1, 1000000, 1000001, 1000000000, 2.5, "4", None, Raw("1e400"), Raw("-0")])
    doc["chunk"] = value
    return doc, "chunk: %s" % dump(value).decode()


def m_job_kind(doc, rng, ctx):
    value = rng.choice(["unknown", "", "Frames", "bricks", "frames", None, 1, ["frames"], "frames\n"])
    doc["kind"] = value
    return doc, "kind: %s" % json.dumps(value)


def m_job_bricks(doc, rng, ctx):
    value = rng.choice(["4096", "16x16x16", "17x16x16", "0", "99999x1x1", "1x1x0", "2x2x1\n", "x", "", "4097",
                        "9999x9999x9999", "-1", "2x2", 8])
    doc["kind"], doc["bricks"] = "bricks", value
    doc.setdefault("merge_output", "field.vdb")
    return doc, "bricks: %s" % json.dumps(value)


LOG_KINDS = ["devzero", "sparse", "long_line", "control", "folder", "plain"]


def m_job_logs(doc, rng, ctx):
    """The job is intact, of 6 one-frame tasks whose logs (read with --array-job) are hostile, one
    kind each in a random order; half the time the job's folder name holds an escape sequence."""
    doc.update(kind="frames", frames=[1, len(LOG_KINDS)], chunk=1, output="out/sky.%04d.exr",
               preview="out/sky.%04d.png")
    ctx["log"] = rng.sample(LOG_KINDS, len(LOG_KINDS))
    what = "task logs: " + ", ".join(ctx["log"])
    if rng.random() < 0.5:  # the folder farm slurm --dir made
        doc["dir"] = ctx["logs_in"] = os.path.join(ctx["dir"], "\x1b[31mjob\x1b[0m")
        what += "; the job folder's name holds an escape sequence"
    return doc, what


def m_job_log_fifo(doc, rng, ctx):
    """The job is intact; one task's log is a FIFO (a reader that opens it waits for a writer)."""
    doc.update(kind="frames", frames=[1, 3], chunk=1, output="out/sky.%04d.exr", preview="")
    ctx["log"] = ["plain", "plain", "plain"]
    ctx["log"][rng.randrange(3)] = "fifo"
    return doc, "task logs: " + ", ".join(ctx["log"])


MUTATIONS = {
    "script": COMMON + [m_script_events, m_script_values],
    "sky": COMMON + [m_sky_clouds],
    "state": COMMON + [m_sky_clouds, m_state_strings],
    "job": COMMON + [m_job_frames, m_job_chunk, m_job_kind, m_job_bricks, m_job_logs, m_job_log_fifo],
}


def mutation_name(m):
    return m.__name__[2:]


# ---------------------------------------------------------------------------------------------
# Cases: a folder, the input, the runs


def make_case(i, a, nimbus, cases_dir):
    kind = KINDS[i % len(KINDS)]
    muts = MUTATIONS[kind]
    mutation = muts[(i // len(KINDS)) % len(muts)]
    rng = random.Random("%d/%d" % (a.seed, i))
    name = "%04d-%s-%s" % (i, kind, mutation_name(mutation))
    d = os.path.join(cases_dir, name)
    jobdir = os.path.join(d, "job")
    f = os.path.join(jobdir, "job.json") if kind == "job" else os.path.join(d, "input.json")
    ctx = {"kind": kind, "dir": d, "jobdir": jobdir, "self": f, "fifo": os.path.join(d, "fifo"),
           "sub": os.path.join(d, "sub"), "nimbus": nimbus}
    docs = seeds(kind, ctx)
    seed_name = rng.choice(sorted(docs))
    out, what = mutation(copy(docs[seed_name]), rng, ctx)
    data = out if isinstance(out, bytes) else dump(out)
    return {"i": i, "name": name, "kind": kind, "mutation": mutation_name(mutation), "seed_doc": seed_name,
            "what": what, "dir": d, "file": f, "data": data, "log": ctx.get("log"), "array_job": i % 8 >= 4,
            "logs": os.path.join(ctx.get("logs_in", jobdir), "logs")}


def write_case(c):
    d = c["dir"]
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(os.path.join(d, "sub"))
    os.mkfifo(os.path.join(d, "fifo"))
    with open(os.path.join(d, "tiny.json"), "w") as f:
        f.write('{"size": [16, 16], "frames": 1}\n')
    # The first frame of docs/viewer.md's file cloud "plume.%04d.vdb": a small foreign fog volume.
    shutil.copyfile(os.path.join(HERE, "corpus", "vdb", "fog_small.vdb"), os.path.join(d, "plume.0001.vdb"))
    os.makedirs(os.path.dirname(c["file"]), exist_ok=True)
    with open(c["file"], "wb") as f:
        f.write(c["data"])
    if c["kind"] == "job":
        write_job_files(c)


def write_job_files(c):
    """Outputs a task might have left (damaged, special files) and the tasks' logs."""
    d, jobdir = c["dir"], os.path.dirname(c["file"])
    out, bricks, logs = os.path.join(d, "out"), os.path.join(jobdir, "bricks"), c["logs"]
    for p in (out, bricks, logs):
        os.makedirs(p, exist_ok=True)
    with open(os.path.join(out, "sky.0001.exr"), "wb") as f:
        f.write(b"\x76\x2f\x31\x01" + bytes(range(256)) * 4)  # EXR magic, then garbage
    os.symlink("/dev/zero", os.path.join(out, "sky.0002.exr"))
    os.mkfifo(os.path.join(out, "sky.0003.exr"))
    with open(os.path.join(out, "sky.0001.png"), "wb") as f:
        f.write(b"not a png")
    with open(os.path.join(out, "sky.0002.png"), "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + b"\x00" * 64)
    with open(os.path.join(bricks, "brick.0000.vdb"), "wb") as f:
        f.write(b"\x20\x42\x44\x56\x00\x00\x00\x00" + bytes(range(256)) * 2)  # VDB magic, then garbage
    os.mkfifo(os.path.join(bricks, "brick.0001.vdb"))
    os.symlink(c["file"], os.path.join(bricks, "brick.0002.vdb"))
    for index, kind in enumerate(c["log"] or ["plain", "empty"]):
        write_log(os.path.join(logs, "task_7_%d.log" % index), kind)
    # The job was submitted before its outputs were written: they are this run's, not stale.
    now = time.time()
    os.utime(c["file"], (now - 100, now - 100))
    for folder in (out, bricks):
        for n in os.listdir(folder):
            os.utime(os.path.join(folder, n), (now, now), follow_symlinks=False)


def write_log(path, kind):
    """A task's log (logs/task_<array>_<index>.log) of one hostile kind."""
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "devzero":
        os.symlink("/dev/zero", path)
    elif kind == "folder":
        os.makedirs(path)
    else:
        with open(path, "wb") as f:
            if kind == "sparse":
                f.truncate(5 << 29)  # 2.5 GiB of NULs, no line break, no disk
            elif kind == "long_line":
                f.write(b"progress " + b"#" * (4 << 20) + b"\n")
            elif kind == "control":
                f.write(b"nimbus: error: \x1b[31mred\x1b[0m\x07\r\n")
            elif kind == "plain":
                f.write(b"starting\nnimbus: error: the task's last line\n")


def runs_of(c, nimbus):
    """(label, argv, names the stderr line may use for the input, farm) of each run of a case."""
    f, d = c["file"], c["dir"]
    view = [nimbus, "--check-only", "view", "--headless", "--script"]
    if c["kind"] == "script":  # a bad record or save_sky file is named by its key and value
        return [("view --script", view + [f], [f, "--script", "script record '", "script save_sky '"], False)]
    cloud = "sky cloud file '"  # a cloud's file that is missing or not a regular file, named by its value
    if c["kind"] == "sky":
        return [("view --sky", view + ["tiny.json", "--sky", f], [f, "--sky", cloud], False)]
    if c["kind"] == "state":
        return [("render --view-state", [nimbus, "--check-only", "render", "--view-state", f, "-o",
                                         os.path.join(d, "out.exr")], [f, "--view-state", cloud], False),
                ("view --state", view + ["tiny.json", "--state", f], [f, "--state", cloud], False)]
    jobdir = os.path.dirname(f)
    extra = ["--array-job", "7"] if c["array_job"] or c["log"] else []
    return [("farm check", [nimbus, "farm", "check", jobdir] + extra, [jobdir, f, "farm job"], True)]


# ---------------------------------------------------------------------------------------------
# Running and checking


def run_one(cmd, cwd, mem_mb, cpu_s, timeout):
    """(exit code or -signal, stdout bytes (first 1 MB), stdout size, stderr bytes (first 1 MB), timed out,
    peak resident MB, wall seconds) of one run."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        p = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                             preexec_fn=limits(mem_mb, cpu_s), start_new_session=True)
        fired = []

        def kill():
            fired.append(True)
            try:
                os.killpg(p.pid, signal.SIGKILL)  # the program and any reader it forked
            except ProcessLookupError:
                pass
        timer = threading.Timer(timeout, kill)
        timer.start()
        try:
            _, status, usage = os.wait4(p.pid, 0)
        finally:
            timer.cancel()
        wall = time.monotonic() - start
        p.returncode = os.waitstatus_to_exitcode(status)
        size = out.seek(0, os.SEEK_END)
        out.seek(0)
        err.seek(0)
        return p.returncode, out.read(1 << 20), size, err.read(1 << 20), bool(fired), usage.ru_maxrss // 1024, wall


def snapshot(d):
    """Every entry below d: kind and mode, size, inode, mtime (lstat: links and FIFOs are not followed)."""
    entries = {}
    for top, dirs, files in os.walk(d):
        for n in dirs + files:
            p = os.path.join(top, n)
            st = os.lstat(p)
            entries[os.path.relpath(p, d)] = (st.st_mode, st.st_size, st.st_ino, st.st_mtime_ns)
    return entries


def diff(before, after):
    changes = []
    for k in sorted(set(before) | set(after)):
        if k not in before:
            changes.append("+" + k)
        elif k not in after:
            changes.append("-" + k)
        elif before[k] != after[k]:
            # A folder whose modification time alone changed: the output checks (check_output_path)
            # made and removed a probe file in it to learn that it takes files; nothing was written.
            if stat.S_ISDIR(before[k][0]) and before[k][:3] == after[k][:3]:
                continue
            changes.append("~" + k)
    return changes


def control_chars(data):
    return sorted({b for b in data if (b < 0x20 and b != 0x0A) or b == 0x7F})


def check(c, farm, names, rc, out, out_size, err, timed_out, rss_mb, rss_limit, changes):
    """The contract's violations for one run, as short texts (empty when it held)."""
    problems = []
    if rss_limit and rss_mb > rss_limit:
        problems.append("peak resident memory %d MB" % rss_mb)
    if changes:
        problems.append("the folder changed: " + " ".join(changes[:6]) + (" ..." if len(changes) > 6 else ""))
    if timed_out or rc < 0 or rc not in (0, 1, 2):
        problems.append(outcome(rc, timed_out))
        return problems
    text = err.decode("utf-8", "replace")
    report = farm and rc == 1 and out_size > 0 and not err  # farm check's list of failed tasks
    if rc != 0 and not report:
        if out_size:
            problems.append("stdout not empty on failure (%d bytes)" % out_size)
        if not text.endswith("\n") or text.count("\n") != 1:
            problems.append("stderr is %d lines, not one" % text.count("\n"))
        elif not any(n in text for n in names):
            problems.append("stderr does not name the input")
    long_lines = [len(line) for line in text.split("\n") if len(line) > MAX_STDERR_LINE]
    if long_lines:
        problems.append("a stderr line of %d characters" % max(long_lines))
    bad = control_chars(err)
    if bad:
        problems.append("control characters in stderr: %s" % " ".join("%02x" % b for b in bad[:8]))
    if farm:
        bad = control_chars(out)
        if bad:
            problems.append("control characters in stdout: %s" % " ".join("%02x" % b for b in bad[:8]))
    if c["mutation"] == "none":
        if not farm and rc != 0:
            problems.append("an intact seed was refused (exit %d)" % rc)
        if farm and not (rc == 0 or report):
            problems.append("farm check of an intact job did not report (exit %d)" % rc)
    return problems


def run_case(c, nimbus, a):
    write_case(c)
    results = []
    for label, cmd, names, farm in runs_of(c, nimbus):
        before = snapshot(c["dir"])
        rc, out, out_size, err, timed_out, rss_mb, wall = run_one(cmd, c["dir"], a.mem_mb, a.cpu_s, a.timeout)
        changes = diff(before, snapshot(c["dir"]))
        problems = check(c, farm, names, rc, out, out_size, err, timed_out, rss_mb, a.rss_mb, changes)
        results.append({"label": label, "cmd": cmd, "rc": rc, "timed_out": timed_out, "rss_mb": rss_mb, "wall": wall,
                        "problems": problems, "err": err.decode("utf-8", "replace"), "out_size": out_size})
    if not a.keep and not any(r["problems"] for r in results):
        shutil.rmtree(c["dir"], ignore_errors=True)
    return c, results


# ---------------------------------------------------------------------------------------------
# Reporting


COLS = ["runs", "exit 0", "exit 1", "exit 2", "crash", "hang", "violations"]


def table(title, groups):
    lines = ["| %s | %s |" % (title, " | ".join(COLS)), "|---|" + "---:|" * len(COLS)]
    for name in groups:
        lines.append("| %s | %s |" % (name, " | ".join(str(groups[name][k]) for k in COLS)))
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nimbus", required=True)
    ap.add_argument("--count", type=int, default=240, help="cases (4 kinds x up to 22 mutations)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--mem-mb", type=int, default=4096, help="address-space limit per run (0: none)")
    ap.add_argument("--rss-mb", type=int, default=2048, help="peak resident memory a run may reach (0: any)")
    ap.add_argument("--cpu-s", type=int, default=30, help="CPU seconds a run may use (0: any)")
    ap.add_argument("--timeout", type=float, default=20, help="wall-clock seconds before a run counts as hung")
    ap.add_argument("--workdir", help="make the case folders here (default: a temporary folder)")
    ap.add_argument("--keep", action="store_true", help="keep every case folder, not only those that broke the contract")
    ap.add_argument("--report", help="also write the tables and violations as Markdown here")
    ap.add_argument("--kinds", help="only these kinds (script, sky, state, job)")
    ap.add_argument("--mutations", help="only these mutations (--list shows them)")
    ap.add_argument("--case", type=int, action="append", help="only case N (repeatable; the numbering of --count)")
    ap.add_argument("--list", action="store_true", help="list the kinds and their mutations, then exit")
    ap.add_argument("--verbose", action="store_true", help="print every run: case, outcome, what was mutated, stderr")
    a = ap.parse_args()

    if a.list:
        for k in KINDS:
            print("%s: %s" % (k, " ".join(mutation_name(m) for m in MUTATIONS[k])))
        return 0
    nimbus = os.path.abspath(a.nimbus)
    if not os.access(nimbus, os.X_OK):
        print("run_hostile_json.py: --nimbus %s is not an executable" % nimbus)
        return 2
    work = os.path.abspath(a.workdir) if a.workdir else tempfile.mkdtemp(prefix="nimbus-hostile-json-")
    cases_dir = os.path.join(work, "cases")
    if a.workdir:
        shutil.rmtree(cases_dir, ignore_errors=True)
    os.makedirs(cases_dir, exist_ok=True)

    kinds = set(a.kinds.split(",")) if a.kinds else set(KINDS)
    mutations = set(a.mutations.split(",")) if a.mutations else None
    indices = a.case if a.case else range(a.count)
    cases = []
    for i in indices:
        c = make_case(i, a, nimbus, cases_dir)
        if c["kind"] in kinds and (mutations is None or c["mutation"] in mutations):
            cases.append(c)

    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        done = list(pool.map(lambda c: run_case(c, nimbus, a), cases))
    seconds = time.monotonic() - start

    totals = collections.Counter()
    by_kind = collections.defaultdict(collections.Counter)
    by_mutation = collections.defaultdict(collections.Counter)
    violations = []
    slowest, largest = (0.0, ""), (0, "")
    for c, results in done:
        for r in results:
            o = outcome(r["rc"], r["timed_out"])
            slowest = max(slowest, (r["wall"], "%s %s" % (r["label"], c["name"])))
            largest = max(largest, (r["rss_mb"], "%s %s" % (r["label"], c["name"])))
            group = "hang" if o == "hang" else "crash" if o.startswith("signal") or o not in (
                "exit 0", "exit 1", "exit 2") else o
            for g in (totals, by_kind[r["label"]], by_mutation[c["mutation"]]):
                g["runs"] += 1
                g[group] += 1
                g["violations"] += bool(r["problems"])
            if a.verbose:
                print("%s %-20s %-7s %s | %s" % (c["name"], r["label"], o, c["what"][:70],
                                                 (r["err"].strip().splitlines() or [""])[0][:200]))
            if r["problems"]:
                line = (r["err"].strip().splitlines() or [""])[0]
                violations.append("%s [%s; seed %s: %s] %s: %s\n    cd %s && %s\n    stderr: %s" % (
                    c["name"], r["label"], c["seed_doc"], c["what"][:160], o, "; ".join(r["problems"]),
                    shlex.quote(c["dir"]), " ".join(shlex.quote(x) for x in r["cmd"]),
                    line[:300] + ("..." if len(line) > 300 else "")))

    summary = ("cases: %d (seed %d), runs: %d, exit 0: %d, exit 1: %d, exit 2: %d, crashes: %d, hangs: %d, "
               "contract violations: %d; %.0f s; slowest run %.2f s (%s); largest peak resident memory %d MB (%s)" % (
                   len(cases), a.seed, totals["runs"], totals["exit 0"], totals["exit 1"], totals["exit 2"],
                   totals["crash"], totals["hang"], totals["violations"], seconds, slowest[0], slowest[1],
                   largest[0], largest[1]))
    text = [summary, ""] + table("run", dict(sorted(by_kind.items()))) + [""] + \
        table("mutation", dict(sorted(by_mutation.items())))
    if violations:
        text += ["", "violations (inputs kept in %s):" % cases_dir] + ["  " + v for v in violations]
    print("\n".join(text))
    if a.report:
        with open(a.report, "w") as f:
            f.write("\n".join(text[:-len(violations) - 2] if violations else text) + "\n")
            if violations:
                f.write("\nviolations (inputs kept in %s):\n\n```\n%s\n```\n" % (cases_dir, "\n".join(violations)))
    if not violations and not a.keep and not a.workdir:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main())
