#!/usr/bin/python3
"""Fuzz.DamagedVdbFilesNeverCrash: runs `nimbus info` on every file make_hostile_vdbs.py writes,
and `nimbus render FILE --scene none --method reference --res 8x8` on every intact file and on every
--render-every'th damaged one, and checks the
command-line contract on each run:

  - the process was not killed by a signal (a crash, an abort, the memory limit's SIGKILL...);
  - the exit code is 0, 1 or 2;
  - on failure stdout is empty and stderr is exactly one line (at most 64 KB) that names the file;
  - an intact, well-formed fog volume (manifest "ok") is read: exit 0;
  - a damaged copy of a file nimbus wrote (sealed, manifest "refused") is refused: exit 1.

Every nimbus run has its address space limited (--mem-mb, default 4096, setrlimit RLIMIT_AS)
so that a runaway allocation fails inside the process instead of taking the machine down, and
a CPU-time limit (--cpu-s, default 60; RLIMIT_CPU) so that a reader spinning on a corrupt count
is stopped (SIGXCPU, counted as a crash), with a last wall-clock guard (--timeout). A
run whose peak resident memory passes --rss-mb (default 2048; wait4's ru_maxrss) breaks the
contract too: these files are a few KB, and only the limit stops some of them from taking
gigabytes.

    run_hostile_vdbs.py --nimbus BIN [--count 266] [--seed 1] [--render-every 4] [--jobs 2] [--rss-mb 2048]
                        [--workdir DIR] [--keep] [--report FILE.md] [--kinds a,b] [--damages a,b]

Prints the counts (files, runs, exit 0/1/2, crashes, contract violations) overall and per kind
and damage, and exits 1 when any run broke the contract.
"""
import argparse
import collections
import concurrent.futures
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from program_runs import limits, outcome  # noqa: E402


def run_one(cmd, mem_mb, cpu_s, timeout):
    """(exit code or -signal, stdout, stderr, timed out, peak resident MB) of one run."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err, preexec_fn=limits(mem_mb, cpu_s))
        fired = []
        timer = threading.Timer(timeout, lambda: (fired.append(True), p.kill()))
        timer.start()
        try:
            _, status, usage = os.wait4(p.pid, 0)  # this child's own peak resident set
        finally:
            timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(status)
        timed_out = bool(fired)
        out.seek(0)
        err.seek(0)
        return (p.returncode, out.read().decode("utf-8", "replace"), err.read(1 << 20).decode("utf-8", "replace"),
                timed_out, usage.ru_maxrss // 1024)


def check(row, verb, path, rc, out, err, timed_out, rss_mb, rss_limit):
    """The contract's violations for one run, as short texts (empty when it held)."""
    problems = []
    if rss_limit and rss_mb > rss_limit and row["kind"] not in LARGE_ON_PURPOSE:
        problems.append("peak resident memory %d MB" % rss_mb)
    kind = outcome(rc, timed_out)
    if timed_out or rc < 0 or rc not in (0, 1, 2):
        problems.append(kind)
        return problems
    if rc != 0:
        if out:
            problems.append("stdout not empty on failure (%d bytes)" % len(out))
        lines = err.split("\n")
        if not err.endswith("\n") or len(lines) != 2:
            problems.append("stderr is %d lines, not one" % err.count("\n"))
        if path not in err:
            problems.append("stderr does not name the file")
        if len(err) > 65536:
            problems.append("stderr is %d bytes" % len(err))
    if row["expect"] == "ok" and rc != 0 and not (verb == "render" and row["kind"] not in RENDERABLE_OK):
        problems.append("an intact file was refused")
    if row["expect"] == "refused" and rc != 1:
        problems.append("a damaged sealed file was not refused (exit %d)" % rc)
    return problems


# Kinds whose intact grid really spans a box of more than 2 GB of floats (make_hostile_vdbs.py):
# reading it densely may take that much memory (or be refused); other files may not.
LARGE_ON_PURPOSE = {"sparse_3gb"}

# Intact kinds whose density grid must also render (multi_grid and many_grids have float grids too).
RENDERABLE_OK = {"fog_small", "fog_dense", "fog_half", "multi_grid", "no_density_name", "many_grids",
                 "nimbus_steam", "nimbus_steam_float", "nimbus_noise"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nimbus", required=True)
    ap.add_argument("--count", type=int, default=266, help="files (38 kinds x 7 damages = 266 covers every pair once)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--render-every", type=int, default=4, help="render every intact file and every k-th damaged one (0: none)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--mem-mb", type=int, default=4096, help="address-space limit per nimbus run (0: none)")
    ap.add_argument("--rss-mb", type=int, default=2048, help="peak resident memory a run may reach (0: any)")
    ap.add_argument("--cpu-s", type=int, default=60, help="CPU seconds a run may use (0: any)")
    ap.add_argument("--timeout", type=float, default=600, help="wall-clock seconds before a run counts as hung")
    ap.add_argument("--workdir", help="write the files here (default: a temporary directory)")
    ap.add_argument("--keep", action="store_true", help="keep the files and outputs")
    ap.add_argument("--report", help="also write the tables as Markdown here")
    ap.add_argument("--kinds")
    ap.add_argument("--damages")
    a = ap.parse_args()

    nimbus = os.path.abspath(a.nimbus)
    work = a.workdir or tempfile.mkdtemp(prefix="nimbus-hostile-")
    if a.workdir:
        shutil.rmtree(work, ignore_errors=True)
    files_dir, out_dir = os.path.join(work, "files"), os.path.join(work, "out")
    os.makedirs(out_dir, exist_ok=True)
    gen = [sys.executable, os.path.join(HERE, "make_hostile_vdbs.py"), files_dir, "--count", str(a.count),
           "--seed", str(a.seed), "--nimbus", nimbus]
    if a.kinds:
        gen += ["--kinds", a.kinds]
    if a.damages:
        gen += ["--damages", a.damages]
    g = subprocess.run(gen)
    if g.returncode != 0:
        print("run_hostile_vdbs.py: the generator failed (%d)" % g.returncode)
        return 1

    with open(os.path.join(files_dir, "manifest.tsv")) as f:
        header = f.readline().rstrip("\n").split("\t")
        rows = [dict(zip(header, line.rstrip("\n").split("\t"))) for line in f if line.strip()]

    jobs = []
    for i, row in enumerate(rows):
        path = os.path.join(files_dir, row["file"])
        jobs.append((row, "info", path, [nimbus, "info", path]))
        if a.render_every > 0 and (row["damage"] == "none" or i % a.render_every == 0):
            exr = os.path.join(out_dir, row["file"] + ".exr")
            jobs.append((row, "render", path, [nimbus, "render", path, "--scene", "none", "--method", "reference",
                                               "--res", "8x8", "-o", exr]))

    def go(job):
        row, verb, path, cmd = job
        rc, out, err, timed_out, rss_mb = run_one(cmd, a.mem_mb, a.cpu_s, a.timeout)
        return row, verb, path, rc, out, err, timed_out, rss_mb

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        results = list(pool.map(go, jobs))

    totals = collections.Counter()
    by_kind = collections.defaultdict(collections.Counter)
    by_damage = collections.defaultdict(collections.Counter)
    failures = []
    peak = (0, "")
    for row, verb, path, rc, out, err, timed_out, rss_mb in results:
        peak = max(peak, (rss_mb, "%s %s" % (verb, row["file"])))
        o = outcome(rc, timed_out)
        crashed = timed_out or rc < 0 or rc not in (0, 1, 2)
        for c in (totals, by_kind[row["kind"]], by_damage[row["damage"]]):
            c["runs"] += 1
            c[verb] += 1
            c["crash" if crashed else o] += 1
        problems = check(row, verb, path, rc, out, err, timed_out, rss_mb, a.rss_mb)
        if problems:
            for c in (totals, by_kind[row["kind"]], by_damage[row["damage"]]):
                c["violations"] += 1
            first = (err.strip().splitlines() or [""])[-1][:200]
            failures.append("%s %s [%s; %s]: %s -- stderr: %s" % (verb, row["file"], row["what"], row["expect"],
                                                                  "; ".join(problems), first))

    cols = ["runs", "info", "render", "exit 0", "exit 1", "exit 2", "crash", "violations"]

    def table(title, groups):
        lines = ["| %s | %s |" % (title, " | ".join(cols)), "|---|" + "---:|" * len(cols)]
        for name in groups:
            c = groups[name]
            lines.append("| %s | %s |" % (name, " | ".join(str(c[k]) for k in cols)))
        return lines

    summary = ["files: %d (seed %d), runs: %d (info %d, render %d), exit 0: %d, exit 1: %d, exit 2: %d, "
               "crashes: %d, contract violations: %d; largest peak resident memory: %d MB (%s)" % (
                   len(rows), a.seed, totals["runs"], totals["info"], totals["render"], totals["exit 0"],
                   totals["exit 1"], totals["exit 2"], totals["crash"], totals["violations"], peak[0], peak[1])]
    text = summary + [""] + table("kind", dict(sorted(by_kind.items()))) + [""] + \
        table("damage", dict(sorted(by_damage.items())))
    if failures:
        text += ["", "violations:"] + ["  " + f for f in failures]
    print("\n".join(text))
    if a.report:
        with open(a.report, "w") as f:
            f.write("\n".join(text) + "\n")
    if not a.keep and not a.workdir:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
