# A cloud's generation: inputs checked, the plan checked against the memory limit, then the VDB(s)
# written, in the caller's thread (run) or on a thread of its own with progress and cancel (Running).
import hashlib
import json
import os
import threading
from dataclasses import dataclass, field

from . import checks, overrides


@dataclass
class Job:
    params: object
    backend: object
    voxel_size: object          # metres, or None for the preset's (times the size factor)
    overrides: dict
    plan: dict
    paths: list = field(default_factory=list)  # one file, or one per frame
    folder: str = ""            # where the files go (any characters, '%' included)
    pattern: str = ""           # sequences: the files' names in the folder, "stem.%04d.vdb" (stem: [A-Za-z0-9_-])


def _file_stem(params, voxel_size, over):
    """preset-<hash of everything that shapes the file>: the same inputs give the same name."""
    key = {"preset": params.preset, "seed": params.seed, "voxel_size": voxel_size, "overrides": over,
           "size": float(params.size), "time": params.time,
           "frames": [params.frame_first, params.frame_last, params.fps] if params.animated else None}
    digest = hashlib.sha1(json.dumps(key, sort_keys=True).encode()).hexdigest()[:12]
    safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in params.preset)
    return f"{safe}-{digest}"


def prepare(params, backend, limit_gib, folder):
    """Checks everything and returns the Job; ValueError (bad input) or RuntimeError/OSError otherwise.

    Nothing is generated here: the plan is nimbus.plan (or the program's probe)."""
    checks.check_inputs(params)
    try:
        doc = backend.preset(params.preset)
    except (ValueError, KeyError) as e:
        raise ValueError(f"preset '{params.preset}': {e}") from None
    over = overrides.build(doc, params)
    voxel_size = float(params.voxel_size) if params.voxel_size > 0 else None  # None: the preset's, times the size
    time = params.frame_time(params.frame_first) if params.animated else params.time
    plan = backend.plan(params.preset, seed=params.seed, voxel_size=voxel_size, time=time, overrides=over,
                        size=float(params.size))
    text = f"{voxel_size:g} m" if voxel_size else f"{float(plan['voxel_size']):g} m (the preset's)"
    checks.check_plan(plan, limit_gib, text)
    job = Job(params, backend, voxel_size, over, plan)
    # The frame field is formatted in the name only, never in the folder: a folder may hold a '%'.
    stem = _file_stem(params, voxel_size, over)
    job.folder = folder
    if params.animated:
        job.pattern = stem + ".%04d.vdb"
        job.paths = [os.path.join(folder, job.pattern % f) for f in params.frames()]
    else:
        job.paths = [os.path.join(folder, stem + ".vdb")]
    return job


class Cancelled(Exception):
    """The user stopped the generation (Esc)."""


def run(job, progress=None, cancel=None):
    """Writes the job's file(s) with its backend. progress(fraction) is called now and then from
    this thread; when the threading.Event cancel is set the backend stops and Cancelled is raised
    (files already complete stay: each is written whole or not at all)."""
    p = job.params
    watch = {"progress": progress or (lambda fraction: None), "cancel": cancel}
    if p.animated:
        job.backend.generate_sequence(job.folder, job.pattern, p.preset, seed=p.seed, voxel_size=job.voxel_size,
                                      overrides=job.overrides, first=p.frame_first, last=p.frame_last,
                                      fps=p.fps, start_frame=p.start_frame(), size=float(p.size), **watch)
    else:
        job.backend.generate_still(job.paths[0], p.preset, seed=p.seed, voxel_size=job.voxel_size,
                                   time=p.time, overrides=job.overrides, size=float(p.size), **watch)
    if cancel is not None and cancel.is_set():
        raise Cancelled("generation cancelled")
    missing = [path for path in job.paths if not os.path.isfile(path)]
    if missing:
        raise RuntimeError(f"nimbus did not write {missing[0]}")


class Running:
    """A job generating on a thread of its own, so that Blender's UI stays live: the operator polls
    fraction and done from a timer, and cancel() (Esc) stops it."""

    def __init__(self, job):
        self.job = job
        self.fraction = 0.0
        self.error = None           # the exception the generation ended with (Cancelled on cancel)
        self._cancel = threading.Event()
        self._thread = threading.Thread(target=self._work, name="nimbus generation", daemon=True)
        self._thread.start()

    def _work(self):
        try:
            run(self.job, progress=self._progress, cancel=self._cancel)
        except BaseException as e:  # noqa: handed to the operator, which reports it
            self.error = Cancelled("generation cancelled") if self._cancel.is_set() else e

    def _progress(self, fraction):
        self.fraction = min(max(float(fraction), 0.0), 1.0)

    @property
    def done(self):
        return not self._thread.is_alive()

    def cancel(self):
        self._cancel.set()

    def wait(self, timeout=None):
        self._thread.join(timeout)
        return self.done
