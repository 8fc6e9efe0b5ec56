#!/usr/bin/env python3
"""Measures nimbus on a private one-node Slurm cluster (tests/farm/private_slurm.py): frames and
bricks run 1 task at a time and 2 at once, against one sequential process (the anchor), with the
scheduler's own overhead (an array of `true`) and the merge's cost. Prints markdown tables for
docs/farm.md. Needs root and scripts/install-deps.sh's Slurm packages.

usage: scripts/farm_bench.py NIMBUS [--frames N] [--voxel-size M] [--preset NAME] [--field-preset NAME]
"""
import argparse
import filecmp
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "farm"))
from private_slurm import PrivateSlurm  # noqa: E402


def timed(argv, env, cwd):
    t0 = time.monotonic()
    r = subprocess.run(argv, env=env, cwd=cwd, capture_output=True, text=True)
    dt = time.monotonic() - t0
    if r.returncode != 0:
        sys.exit(f"{' '.join(argv)} failed ({r.returncode}):\n{r.stdout}{r.stderr}")
    return dt, r.stdout


def job_times(job_id, env):
    """(first start, last end) of a job or of every task of an array, epoch seconds, from the
    controller's record (1 s resolution; completed jobs stay there for MinJobAge, 300 s)."""
    from datetime import datetime
    out = subprocess.run(["scontrol", "show", "job", "-o", job_id], env=env, capture_output=True, text=True).stdout
    starts = [datetime.fromisoformat(t).timestamp() for t in re.findall(r"StartTime=(\S+)", out)]
    ends = [datetime.fromisoformat(t).timestamp() for t in re.findall(r"EndTime=(\S+)", out)]
    return min(starts), max(ends)


def spans(stdout, env):
    """Seconds from the array's first task start to its last end, and to the end of the last job."""
    ids = [re.search(p, stdout) for p in (r"task array (\d+)", r"check (\d+)", r"merge (\d+)")]
    ids = [m.group(1) for m in ids if m]
    a0, a1 = job_times(ids[0], env)
    _, last = job_times(ids[-1], env)
    return a1 - a0, last - a0


def task_seconds(logdir):
    """Seconds nimbus itself reports for each task's work ("..., 1.23 s" on its "wrote" lines)."""
    total = []
    for name in sorted(os.listdir(logdir)):
        if name.startswith("task_"):
            text = open(os.path.join(logdir, name)).read()
            total.append(sum(float(s) for s in re.findall(r"^wrote .*, ([0-9.]+) s$", text, re.M)))
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("nimbus")
    ap.add_argument("--frames", type=int, default=8)
    ap.add_argument("--preset", default="cumulus-congestus")
    ap.add_argument("--frame-voxel-size", default="8")
    ap.add_argument("--field-preset", default="cumulus-field")
    ap.add_argument("--voxel-size", default="12")
    a = ap.parse_args()
    nimbus = os.path.abspath(a.nimbus)
    work = tempfile.mkdtemp(prefix="nimbus-farm-bench-")
    cluster = PrivateSlurm(os.path.join(work, "cluster")).__enter__()
    env = cluster.env
    try:
        rows = []
        # The scheduler alone: 4 tasks of `true`, 2 at once, then a dependent job.
        _, out = timed(["sbatch", "--parsable", "--wait", "--array=0-3%2", "--output=/dev/null", "--wrap=true"], env, work)
        a0, a1 = job_times(out.strip().split(";")[0], env)
        rows.append(("Slurm alone: a 4-task array of `true`, 2 at once", "2", f"{a1 - a0:.0f}", "-",
                     "the scheduler's own latency (sched_interval 1 s)"))

        frames = ["generate", "--preset", a.preset, "--voxel-size", a.frame_voxel_size, "--frames", f"1-{a.frames}"]
        t_seq, out = timed([nimbus, *frames, "-o", "seq/f.%04d.vdb"], env, work)
        rows.append((f"frames: one process, {a.frames} frames in sequence (anchor)", "1", f"{t_seq:.1f}", "1.00", "-"))
        for conc, cpus in ((1, 2), (2, 1)):
            d = f"job-frames-{conc}"
            _, out = timed([nimbus, "farm", "slurm", "--dir", d, "--concurrency", str(conc), "--cpus-per-task", str(cpus),
                            "--wait", "--", *frames, "-o", f"{d}-out/f.%04d.vdb"], env, work)
            t_array, t = spans(out, env)
            same = all(filecmp.cmp(f"{work}/seq/f.{f:04d}.vdb", f"{work}/{d}-out/f.{f:04d}.vdb", shallow=False)
                       for f in range(1, a.frames + 1))
            work_s = sum(task_seconds(f"{work}/{d}/logs"))
            rows.append((f"frames: Slurm array + check, {conc} task(s) at once", str(conc), f"{t_array:.0f} / {t:.0f}",
                         f"{t_seq / t_array:.2f}", f"tasks' own work {work_s:.1f} s; files identical: {same}"))

        field = ["generate", "--preset", a.field_preset, "--voxel-size", a.voxel_size]
        t_whole, out = timed([nimbus, *field, "-o", "whole.vdb"], env, work)
        active = re.search(r"(\d+) active voxels", out).group(1)
        rows.append((f"bricks: one process, the whole field (anchor; {active} active voxels, "
                     f"{os.path.getsize(f'{work}/whole.vdb') / 2**20:.1f} MiB)", "1", f"{t_whole:.1f}", "1.00", "-"))
        brick_rows = []
        for conc, cpus in ((1, 2), (2, 1)):
            d = f"job-bricks-{conc}"
            _, out = timed([nimbus, "farm", "slurm", "--dir", d, "--bricks", "2x2x1", "--concurrency", str(conc),
                            "--cpus-per-task", str(cpus), "--wait", "--", *field, "-o", f"{d}.vdb"], env, work)
            t_array, t = spans(out, env)
            merge = re.search(r"read and joined in ([0-9.]+) s, written in ([0-9.]+) s, peak memory (\d+) MiB", out)
            same = filecmp.cmp(f"{work}/whole.vdb", f"{work}/{d}.vdb", shallow=False)
            per = task_seconds(f"{work}/{d}/logs")
            rows.append((f"bricks: 2x2x1 array + check + merge, {conc} task(s) at once", str(conc), f"{t_array:.0f} / {t:.0f}",
                         f"{t_whole / t_array:.2f}",
                         f"bricks' own work {sum(per):.1f} s; merge read+join {merge.group(1)} s, write {merge.group(2)} s, "
                         f"{merge.group(3)} MiB; file identical: {same}"))
            if conc == 1:
                for i in range(4):
                    log = open(f"{work}/{d}/logs/" + [n for n in os.listdir(f"{work}/{d}/logs") if n.endswith(f"_{i}.log") and n.startswith("task_")][0]).read()
                    box = re.search(r"(\d+ x \d+ x \d+) voxels, at most (\d+) MiB", log)
                    peak = re.search(r"peak memory (\d+) MiB", log).group(1)
                    act = re.search(r"(\d+) active voxels", log).group(1)
                    size = os.path.getsize(f"{work}/{d}/bricks/brick.{i:04d}.vdb") / 2**20
                    brick_rows.append((str(i), box.group(1), act, f"{per[i]:.2f}", box.group(2), peak, f"{size:.2f}"))
        print("| run | tasks at once | wall s: array / to the last job's end (1 s steps) | speed-up of the array vs anchor | notes |")
        print("|---|---|---|---|---|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
        print()
        print("| brick | box (voxels) | active voxels | generate s | dense bound MiB | peak RSS MiB | file MiB |")
        print("|---|---|---|---|---|---|---|")
        for r in brick_rows:
            print("| " + " | ".join(r) + " |")
    finally:
        cluster.stop()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
