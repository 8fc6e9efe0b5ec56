# The nimbus program as the backend: subprocess with a list argv (never a shell).
import json
import math
import os
import re
import shutil
import subprocess
import tempfile

# Probes and checks take well under a second; a stuck program is cut off after this.
PROBE_TIMEOUT_S = 120
# The plan probe: a coarse grid whose index box gives the cloud's extent.
PROBE_RES = 64

_BOX = re.compile(r"index box \[(-?\d+) (-?\d+) (-?\d+) \.\. (-?\d+) (-?\d+) (-?\d+)\]")
_VOXEL = re.compile(r"voxel ([0-9.eE+-]+) m")


def find_program(preference=""):
    """NIMBUS_PROGRAM, else the add-on preference, else `nimbus` on PATH; None when none is found."""
    for candidate in (os.environ.get("NIMBUS_PROGRAM", ""), preference):
        if candidate:
            return candidate
    return shutil.which("nimbus")


class ProgramBackend:
    name = "program"

    def __init__(self, program):
        if not program:
            raise RuntimeError("nimbus program not found: install nimbus on PATH, set NIMBUS_PROGRAM "
                               "or the add-on preference 'nimbus program'")
        if not (os.path.isfile(program) and os.access(program, os.X_OK)):
            raise RuntimeError(f"nimbus program '{program}': not an executable file "
                               "(NIMBUS_PROGRAM or the add-on preference 'nimbus program')")
        self.program = os.path.abspath(program)  # sequences run in the cache folder
        self._presets = {}

    def describe(self):
        return f"program {self.program}"

    def _run(self, argv, timeout=PROBE_TIMEOUT_S, bad_input=True, cwd=None):
        """Runs nimbus with argv (in the folder cwd); a non-zero exit raises ValueError (usage) or RuntimeError."""
        try:
            r = subprocess.run([self.program] + argv, capture_output=True, text=True, timeout=timeout, cwd=cwd,
                               stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            raise RuntimeError(f"nimbus {argv[0]}: no answer after {timeout} s") from None
        if r.returncode != 0:
            message = (r.stderr.strip() or r.stdout.strip() or f"exit status {r.returncode}").splitlines()[-1]
            message = message.removeprefix("nimbus: error: ").removeprefix("nimbus: ")
            # Exit 2 is a usage error: the arguments are at fault.
            raise (ValueError if r.returncode == 2 and bad_input else RuntimeError)(message)
        return r.stdout

    def presets(self):
        out = self._run(["presets"])
        return [line.split()[0] for line in out.splitlines() if line.strip()]

    def preset(self, name):
        if name not in self._presets:
            self._presets[name] = json.loads(self._run(["presets", "show", name]))
        return self._presets[name]

    @staticmethod
    def _cloud_args(preset, seed, voxel_size, overrides):
        argv = ["--preset", preset]
        if seed is not None:
            argv += ["--seed", str(int(seed))]
        if voxel_size is not None:
            argv += ["--voxel-size", repr(float(voxel_size))]
        for key, value in (overrides or {}).items():
            argv += ["--set", f"{key}={json.dumps(value)}"]
        return argv

    def plan(self, preset, *, seed=None, voxel_size=None, res=None, time=0.0, overrides=None):
        """nimbus.plan's dict, from --check-only and a coarse probe (the box to within two coarse voxels)."""
        cloud = self._cloud_args(preset, seed, None, overrides)
        with tempfile.TemporaryDirectory(prefix="nimbus-plan-") as tmp:
            out = os.path.join(".", "plan.vdb")  # in tmp (cwd): a '%' in TMPDIR is no frame field
            check = (["generate"] + self._cloud_args(preset, seed, voxel_size, overrides) +
                     ["--time", repr(float(time)), "-o", out])
            if res is not None:
                check += ["--res", str(int(res))]
            self._run(["--check-only"] + check, cwd=tmp)
            text = self._run(["generate"] + cloud + ["--time", repr(float(time)), "--res", str(PROBE_RES),
                                                    "--brick", "0/1", "-o", out], cwd=tmp)
        box, voxel = _BOX.search(text), _VOXEL.search(text)
        if not box or not voxel:
            raise RuntimeError(f"nimbus generate: unexpected output for the plan probe: {text.strip()[:200]}")
        lo = [int(v) for v in box.groups()[:3]]
        hi = [int(v) for v in box.groups()[3:]]
        coarse = float(voxel.group(1))
        b0 = [i * coarse for i in lo]
        b1 = [i * coarse for i in hi]
        if res is not None:
            vs = max(b - a for a, b in zip(b0, b1)) / int(res)
        elif voxel_size is not None:
            vs = float(voxel_size)
        else:
            vs = float(self.preset(preset).get("voxel_size", coarse))
        dims = tuple(int(math.floor(b / vs)) - int(math.floor(a / vs)) + 2 for a, b in zip(b0, b1))
        return {"voxel_size": vs, "dims": dims, "dense_bytes": 4 * dims[0] * dims[1] * dims[2],
                "bounds_m": (tuple(b0), tuple(b1))}

    def generate_still(self, path, preset, *, seed, voxel_size, time, overrides):
        """Writes path. The program runs in path's folder and is given the file's name alone (which
        holds no '%'): it reads every '%' of -o as a frame field, and the folder may hold one."""
        folder, name = os.path.split(os.path.abspath(path))
        self._run(["generate"] + self._cloud_args(preset, seed, voxel_size, overrides) +
                  ["--time", repr(float(time)), "-o", os.path.join(".", name)], timeout=None, cwd=folder)

    def generate_sequence(self, folder, pattern, preset, *, seed, voxel_size, overrides, first, last, fps, start_frame):
        """Writes folder/(pattern % frame) for frames first..last; frame n at time (n - start_frame) / fps.
        The program runs in the folder and is given the name pattern alone: the program reads every
        '%' of -o as a frame field, and the folder may hold one."""
        self._run(["generate"] + self._cloud_args(preset, seed, voxel_size, overrides) +
                  ["--frames", f"{first}-{last}", "--fps", repr(float(fps)), "--start-frame", str(int(start_frame)),
                   "-o", os.path.join(".", pattern)], timeout=None, cwd=folder)
