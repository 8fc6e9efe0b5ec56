"""A private one-node Slurm cluster for tests and trials: munged, slurmctld and slurmd on
127.0.0.1 with their keys, config, state, spool and logs in one directory, on free ports, no
systemd. Needs root (slurmd runs jobs as their user) and the
Debian packages munge, slurmctld, slurmd and slurm-client (scripts/install-deps.sh installs them).

    with PrivateSlurm(directory) as cluster:
        subprocess.run(["sbatch", ...], env=cluster.env)

or from a shell: python3 private_slurm.py start DIR (prints `export SLURM_CONF=...`), then
python3 private_slurm.py stop DIR.
"""
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

NODE = "nimbus0"


class SlurmUnavailable(RuntimeError):
    """The cluster could not start; the message is one line saying why."""


def _free_ports(n):
    socks = [socket.socket() for _ in range(n)]
    try:
        for s in socks:
            s.bind(("127.0.0.1", 0))
        return [s.getsockname()[1] for s in socks]
    finally:
        for s in socks:
            s.close()


def _wait_for(what, predicate, seconds, log):
    """Polls `predicate` until it holds; SlurmUnavailable naming `what` and `log` after `seconds`.
    (Daemons say nothing when they are ready, so readiness is polled, with a deadline.)"""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if predicate():
            return
        time.sleep(0.1)
    tail = ""
    if log and os.path.exists(log):
        lines = [l for l in open(log, errors="replace").read().splitlines() if l.strip()]
        tail = ": " + (lines[-1] if lines else "(empty log)")
    raise SlurmUnavailable(f"{what} did not become ready within {seconds} s (log {log}{tail})")


class PrivateSlurm:
    def __init__(self, directory, cpus=2, memory_mb=4000):
        self.dir = os.path.abspath(directory)
        self.cpus = cpus
        self.memory_mb = memory_mb
        self.conf = os.path.join(self.dir, "slurm.conf")
        self.env = dict(os.environ, SLURM_CONF=self.conf)

    def _path(self, *parts):
        return os.path.join(self.dir, *parts)

    def start(self):
        if os.geteuid() != 0:
            raise SlurmUnavailable("the private Slurm cluster needs root (slurmd runs jobs as their user); run as root")
        for prog in ("munged", "slurmctld", "slurmd", "sbatch", "scontrol", "sinfo"):
            if not shutil.which(prog, path=os.environ.get("PATH", "") + ":/usr/sbin:/sbin"):
                raise SlurmUnavailable(f"{prog} is not installed: run scripts/install-deps.sh (munge, slurmctld, slurmd, slurm-client)")
        os.makedirs(self.dir, exist_ok=True)
        os.chmod(self.dir, 0o711)  # munged wants its socket's directory searchable, not writable, by others
        for d in ("state", "spool", "log"):
            os.makedirs(self._path(d), exist_ok=True)
        key = self._path("munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        ctld_port, slurmd_port = _free_ports(2)
        with open(self.conf, "w") as f:
            f.write(f"""# A private one-node cluster (tests/farm/private_slurm.py)
ClusterName=nimbus
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
AuthType=auth/munge
AuthInfo=socket={self._path("munge.sock")}
CredType=cred/munge
StateSaveLocation={self._path("state")}
SlurmdSpoolDir={self._path("spool")}
SlurmctldPidFile={self._path("slurmctld.pid")}
SlurmdPidFile={self._path("slurmd.pid")}
SlurmctldLogFile={self._path("log", "slurmctld.log")}
SlurmdLogFile={self._path("log", "slurmd.log")}
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1,sched_min_interval=100000
MpiDefault=none
ReturnToService=2
NodeName={NODE} NodeHostname=localhost NodeAddr=127.0.0.1 CPUs={self.cpus} RealMemory={self.memory_mb} State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
""")
        self._run(["munged", f"--key-file={key}", f"--socket={self._path('munge.sock')}",
                   f"--pid-file={self._path('munged.pid')}", f"--log-file={self._path('log', 'munged.log')}",
                   f"--seed-file={self._path('munge.seed')}", "--force"], "munged", self._path("log", "munged.log"))
        self._run(["slurmctld", "-f", self.conf], "slurmctld", self._path("log", "slurmctld.log"))
        _wait_for("slurmctld", lambda: self._quiet(["scontrol", "ping"]) and
                  "UP" in self._output(["scontrol", "ping"]), 30, self._path("log", "slurmctld.log"))
        self._run(["slurmd", "-f", self.conf, "-N", NODE], "slurmd", self._path("log", "slurmd.log"))
        _wait_for("slurmd (node idle)", lambda: self._output(["sinfo", "-h", "-n", NODE, "-o", "%T"]).strip() == "idle",
                  30, self._path("log", "slurmd.log"))
        return self

    def stop(self):
        """Stops the daemons and waits for them to exit."""
        self._quiet(["scontrol", "shutdown"])
        for name in ("slurmd", "slurmctld", "munged"):
            pidfile = self._path(f"{name}.pid")
            try:
                pid = int(open(pidfile).read().split()[0])
            except (OSError, ValueError, IndexError):
                continue
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                continue
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline:
                try:
                    os.kill(pid, 0)
                except ProcessLookupError:
                    break
                time.sleep(0.1)
            else:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass

    def __enter__(self):
        try:
            return self.start()
        except BaseException:
            self.stop()
            raise

    def __exit__(self, *exc):
        self.stop()

    def _run(self, argv, name, log):
        r = subprocess.run(argv, env=self.env, capture_output=True, text=True)
        if r.returncode != 0:
            said = (r.stderr or r.stdout).strip().splitlines()
            raise SlurmUnavailable(f"{name} did not start (exit {r.returncode}): {said[-1] if said else 'see ' + log}")

    def _quiet(self, argv):
        return subprocess.run(argv, env=self.env, capture_output=True).returncode == 0

    def _output(self, argv):
        return subprocess.run(argv, env=self.env, capture_output=True, text=True).stdout


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("start", "stop"):
        sys.exit("usage: private_slurm.py start|stop DIR")
    cluster = PrivateSlurm(sys.argv[2])
    if sys.argv[1] == "stop":
        cluster.stop()
    else:
        try:
            cluster.start()
        except SlurmUnavailable as e:
            cluster.stop()
            sys.exit(f"private Slurm: {e}")
        print(f"export SLURM_CONF={cluster.conf}")
