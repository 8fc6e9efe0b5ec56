"""Farm.SlurmOneNode: nimbus's frames and bricks run as Slurm job arrays on a private one-node
cluster (private_slurm.py), checked against one sequential process:
  - a 4-frame array: every frame equals the sequential run's, byte for byte;
  - a 2x2x1 brick job with its merge: the joined grid equals the one-process grid voxel for voxel
    (read by OpenVDB's own Python module, not by nimbus) and byte for byte;
  - a task cancelled by the scheduler is reported by its index by the check job;
  - a task that fails (its output cannot be written) is retried, then reported with its log.
If the cluster cannot start (no root, a missing package, a port taken) the test fails with one
line saying why; it never skips.

usage: run_slurm_farm.py NIMBUS WORKDIR
"""
import filecmp
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from private_slurm import PrivateSlurm, SlurmUnavailable  # noqa: E402

FAILURES = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        FAILURES.append(what)


def run(argv, env, cwd, expect=0):
    r = subprocess.run(argv, env=env, cwd=cwd, capture_output=True, text=True, timeout=600)
    if expect is not None and r.returncode != expect:
        print(f"command {' '.join(argv)} exited {r.returncode}, expected {expect}:\n{r.stdout}{r.stderr}", flush=True)
    return r


def job_ids(stdout):
    array = re.search(r"task array (\d+)", stdout)
    chk = re.search(r"check (\d+)", stdout)
    return (array.group(1) if array else None, chk.group(1) if chk else None)


def grid_voxels(path):
    import pyopenvdb as vdb
    grids = {}
    for g in vdb.readAllGridMetadata(path):
        grid = vdb.read(path, g.name)
        grids[g.name] = {tuple(v.min): v.value for v in grid.citerOnValues()}
    return grids


def main():
    nimbus, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    try:
        cluster = PrivateSlurm(os.path.join(work, "cluster")).__enter__()
    except SlurmUnavailable as e:
        print(f"Farm.SlurmOneNode: Slurm could not start: {e}", flush=True)
        return 1
    env = cluster.env
    try:
        frames = ["generate", "--preset", "cumulus-humilis", "--voxel-size", "10", "--frames", "1-4"]
        # 1. A 4-frame array, two tasks at once, against one sequential run.
        run([nimbus, *frames, "-o", "seq/f.%04d.vdb"], env, work)
        r = run([nimbus, "farm", "slurm", "--dir", "job-frames", "--concurrency", "2", "--wait", "--",
                 *frames, "-o", "farm/f.%04d.vdb"], env, work)
        check(r.returncode == 0 and "all 4 task(s) complete" in r.stdout, "frame array: the check job passed")
        for f in range(1, 5):
            a, b = f"{work}/seq/f.{f:04d}.vdb", f"{work}/farm/f.{f:04d}.vdb"
            check(os.path.exists(b) and filecmp.cmp(a, b, shallow=False), f"frame {f}: the task's file equals the sequential run's, byte for byte")
        logs = os.listdir(f"{work}/job-frames/logs")
        check(len([l for l in logs if l.startswith("task_")]) == 4, "frame array: one log per task")

        # 2. A 2x2x1 brick job with its merge, against the field generated in one process.
        field = ["generate", "--preset", "cumulus-field", "--voxel-size", "40"]
        run([nimbus, *field, "-o", "whole.vdb"], env, work)
        r = run([nimbus, "farm", "slurm", "--dir", "job-bricks", "--bricks", "2x2x1", "--wait", "--", *field,
                 "-o", "merged.vdb"], env, work)
        check(r.returncode == 0 and "4 bricks of 2x2x1 joined" in r.stdout, "brick job: check and merge passed")
        whole, merged = grid_voxels(f"{work}/whole.vdb"), grid_voxels(f"{work}/merged.vdb")
        check(len(whole.get("density", {})) > 50000, "the one-process field has its voxels")
        check(whole == merged, "the merged grid equals the one-process grid voxel for voxel (pyopenvdb)")
        check(filecmp.cmp(f"{work}/whole.vdb", f"{work}/merged.vdb", shallow=False), "the merged file equals the one-process file byte for byte")
        bricks = [grid_voxels(f"{work}/job-bricks/bricks/brick.{i:04d}.vdb")["density"] for i in range(4)]
        check(all(len(b) > 0 for b in bricks) and sum(len(b) for b in bricks) == len(whole["density"]),
              "every brick holds part of the field and no voxel twice")

        # 3. A task cancelled by the scheduler (held array; task 2 cancelled; the rest released).
        r = run([nimbus, "farm", "slurm", "--dir", "job-kill", "--hold", "--", *frames, "-o", "kill/f.%04d.vdb"], env, work)
        array, chk = job_ids(r.stdout)
        check(array is not None and chk is not None, "held array submitted")
        run(["scancel", f"{array}_2"], env, work)
        run(["scontrol", "release", array], env, work)
        run(["sbatch", "--wait", f"--dependency=afterany:{chk}", "--output=/dev/null", "--wrap=true"], env, work)
        log = open(f"{work}/job-kill/logs/check_{chk}.log").read()
        print(log, end="")
        check(re.search(r"^task 2 \(frame 3\): missing kill/f\.0003\.vdb", log, re.M) is not None, "the cancelled task is reported by index")
        check(len(re.findall(r"^task \d", log, re.M)) == 1 and "1 of 4 task(s) failed" in log, "and only it")

        # 4. A task that fails: its frame's output is a directory, which nimbus refuses to replace.
        os.makedirs(f"{work}/fail/f.0002.vdb")
        r = run([nimbus, "farm", "slurm", "--dir", "job-fail", "--retries", "1", "--wait", "--", *frames,
                 "-o", "fail/f.%04d.vdb"], env, work, expect=1)
        check(r.returncode == 1 and re.search(r"^task 1 \(frame 2\): .*f\.0002\.vdb; log .*task_\d+_1\.log: nimbus farm: task 1 failed", r.stdout, re.M) is not None,
              "the failed task is reported by index, with its log")
        array, _ = job_ids(r.stdout)
        task_log = open(f"{work}/job-fail/logs/task_{array}_1.log").read()
        check(task_log.count("attempt") == 2, "the failed task ran twice (--retries 1)")
    finally:
        cluster.stop()
    print(f"Farm.SlurmOneNode: {len(FAILURES)} failure(s)" if FAILURES else "Farm.SlurmOneNode: all checks passed", flush=True)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
