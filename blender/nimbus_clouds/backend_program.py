# The nimbus program as the backend: subprocess with a list argv (never a shell).
import json
import re
import os
import shutil
import subprocess
import tempfile

# Plans and checks take well under a second; a stuck program is cut off after this.
PROBE_TIMEOUT_S = 120
# How often a running generation reports its progress and looks for a cancel, seconds.
POLL_S = 0.1


_PROGRESS = re.compile(r"(?: frame (-?\d+))?: +(\d+) %$", re.MULTILINE)


def _fraction_done(stderr_text, frames):
    """The share of the work done, from the program's last progress line (progress.hpp) over the
    frames (None: a still)."""
    found = list(_PROGRESS.finditer(stderr_text))
    if not found:
        return 0.0
    frame, percent = found[-1].group(1), float(found[-1].group(2)) / 100.0
    if not frames or frame is None:
        return percent
    return (frames.index(int(frame)) + percent) / len(frames) if int(frame) in frames else 0.0


def _failure(code, output, bad_input=True):
    """The exception for a run that exited `code`, with the last line of its output: ValueError
    for exit 2 (a usage error: the arguments are at fault), else RuntimeError."""
    message = (output.splitlines()[-1] if output else f"exit status {code}")
    message = message.removeprefix("nimbus: error: ").removeprefix("nimbus: ")
    return (ValueError if code == 2 and bad_input else RuntimeError)(message)


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
            raise _failure(r.returncode, r.stderr.strip() or r.stdout.strip(), bad_input)
        return r.stdout

    def presets(self):
        out = self._run(["presets"])
        return [line.split()[0] for line in out.splitlines() if line.strip()]

    def preset(self, name):
        if name not in self._presets:
            self._presets[name] = json.loads(self._run(["presets", "show", name]))
        return self._presets[name]

    @staticmethod
    def _cloud_args(preset, seed, voxel_size, overrides, size=1.0):
        argv = ["--preset", preset]
        if seed is not None:
            argv += ["--seed", str(int(seed))]
        if voxel_size is not None:
            argv += ["--voxel-size", repr(float(voxel_size))]
        if size != 1.0:
            argv += ["--size", repr(float(size))]
        for key, value in (overrides or {}).items():
            argv += ["--set", f"{key}={json.dumps(value)}"]
        return argv

    def plan(self, preset, *, seed=None, voxel_size=None, res=None, time=0.0, overrides=None, size=1.0):
        """nimbus.plan's dict: `nimbus generate --plan-json` (the program's own checks, no voxel)."""
        argv = (["generate"] + self._cloud_args(preset, seed, voxel_size, overrides, size) +
                ["--time", repr(float(time)), "--plan-json"])
        if res is not None:
            argv += ["--res", str(int(res))]
        text = self._run(argv)
        try:
            plan = json.loads(text)
        except json.JSONDecodeError:
            raise RuntimeError(f"nimbus generate --plan-json: not JSON: {text.strip()[:200]}") from None
        plan["dims"] = tuple(plan["dims"])
        for key in ("bounds_m", "index_box"):
            if plan.get(key) is not None:
                plan[key] = tuple(tuple(corner) for corner in plan[key])
        return plan

    def _run_watched(self, argv, cwd, frames, progress, cancel):
        """Runs a generation in cwd. Every POLL_S: progress(the fraction done), read from the
        program's progress lines ("PRESET frame N:  45 %" on stderr, once a second) over `frames`
        (the frame numbers; None for a still), and a look at cancel, which stops the program
        (SIGTERM, then SIGKILL) and raises Cancelled."""
        from .generation import Cancelled
        done = 0.0
        with tempfile.TemporaryFile(mode="w+") as err:
            proc = subprocess.Popen([self.program] + argv, cwd=cwd, stdin=subprocess.DEVNULL,
                                    stdout=subprocess.DEVNULL, stderr=err, text=True)
            while True:
                try:
                    code = proc.wait(timeout=POLL_S)
                    break
                except subprocess.TimeoutExpired:
                    pass
                if cancel is not None and cancel.is_set():
                    proc.terminate()
                    try:
                        proc.wait(timeout=5)
                    except subprocess.TimeoutExpired:
                        proc.kill()
                        proc.wait()
                    raise Cancelled("generation cancelled")
                if progress is not None:
                    err.seek(0)
                    done = max(done, _fraction_done(err.read(), frames))
                    progress(done)
            if code != 0:
                err.seek(0)
                raise _failure(code, err.read().strip())

    def generate_still(self, path, preset, *, seed, voxel_size, time, overrides, size=1.0, progress=None, cancel=None):
        """Writes path. The program runs in path's folder and is given the file's name alone (which
        holds no '%'): it reads every '%' of -o as a frame field, and the folder may hold one."""
        folder, name = os.path.split(os.path.abspath(path))
        self._run_watched(["generate"] + self._cloud_args(preset, seed, voxel_size, overrides, size) +
                          ["--time", repr(float(time)), "-o", os.path.join(".", name)], folder, None, progress, cancel)

    def generate_sequence(self, folder, pattern, preset, *, seed, voxel_size, overrides, first, last, fps, start_frame,
                          size=1.0, progress=None, cancel=None):
        """Writes folder/(pattern % frame) for frames first..last; frame n at time (n - start_frame) / fps.
        The program runs in the folder and is given the name pattern alone: the program reads every
        '%' of -o as a frame field, and the folder may hold one."""
        frames = list(range(first, last + 1))
        self._run_watched(["generate"] + self._cloud_args(preset, seed, voxel_size, overrides, size) +
                          ["--frames", f"{first}-{last}", "--fps", repr(float(fps)), "--start-frame",
                           str(int(start_frame)), "-o", os.path.join(".", pattern)], folder, frames, progress, cancel)
