# Input checks before any generation: each bad value is refused with a message naming it.
import math
import os

SEED_MAX = 2**32 - 1       # nimbus seeds are uint32
MAX_FRAMES = 10000         # nimbus generate --frames refuses more without --many-frames
BLENDER_MAX_FRAME = 1048574  # Blender's last frame (MAXFRAME): a Volume's frames beyond it never play
START_FRAME_MAX = 9999999    # nimbus's --start-frame range, +-9999999 (samples/cli/frame_range.hpp)
GIB = 1024.0**3


def machine_memory_bytes():
    """Total RAM: /proc/meminfo's MemTotal, else sysconf, else 16 GiB."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return 16 * 1024**3


def default_memory_limit_gib():
    """The default dense-size limit: a quarter of the machine's RAM, in GiB."""
    return round(machine_memory_bytes() / 4.0 / GIB, 2)


def _finite(name, value):
    if not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{name}: must be a finite number, got {value!r}")


def check_inputs(p):
    """Refuses bad CloudParams (see params.py) with ValueError naming the input."""
    if not p.preset:
        raise ValueError("preset: none chosen (is the nimbus module or program available?)")
    if p.seed is not None:
        if not isinstance(p.seed, int) or not 0 <= p.seed <= SEED_MAX:
            raise ValueError(f"seed {p.seed}: nimbus seeds are whole numbers from 0 to {SEED_MAX}")
    _finite("voxel size", p.voxel_size)
    if p.voxel_size < 0:
        raise ValueError(f"voxel size {p.voxel_size:g} m: must be > 0 metres (0 = the preset's)")
    _finite("time", p.time)
    if p.time < 0:
        raise ValueError(f"time {p.time:g} s: must be >= 0 seconds")
    _finite("size factor", p.size)
    if not p.size > 0:
        raise ValueError(f"size factor {p.size:g}: must be > 0")
    if p.coverage is not None:
        _finite("coverage", p.coverage)
        if not 0.0 <= p.coverage <= 1.0:
            raise ValueError(f"coverage {p.coverage:g}: must be in [0, 1]")
    if p.density is not None:
        _finite("density", p.density)
        if p.density < 0:
            raise ValueError(f"density {p.density:g}: must be >= 0")
    if p.animated:
        if p.frame_first < 0:
            raise ValueError(f"first frame {p.frame_first}: must be >= 0 (files are numbered name.%04d.vdb)")
        if p.frame_last < p.frame_first:
            raise ValueError(f"last frame {p.frame_last}: must not be before the first frame {p.frame_first}")
        if p.frame_last > BLENDER_MAX_FRAME:
            raise ValueError(f"last frame {p.frame_last}: Blender's frames end at {BLENDER_MAX_FRAME}; "
                             f"the files of later frames would never play")
        if p.frame_last - p.frame_first + 1 > MAX_FRAMES:
            raise ValueError(f"frames {p.frame_first}-{p.frame_last}: more than {MAX_FRAMES} frames")
        _finite("fps", p.fps)
        if not p.fps > 0:
            raise ValueError(f"fps {p.fps:g}: must be > 0")
        # The first frame is at `time`: the frame at time 0 (nimbus's --start-frame) must be one the
        # program takes, whichever backend runs, so that both make the same files.
        start = p.frame_first - round(p.time * p.fps)
        if abs(start) > START_FRAME_MAX:
            raise ValueError(f"time {p.time:g} s: at {p.fps:g} fps time 0 would be frame {start:g}, beyond "
                             f"nimbus's +-{START_FRAME_MAX} (an animation starts within {START_FRAME_MAX / p.fps:g} s "
                             f"of time 0)")


def check_plan(plan, limit_gib, voxel_size_text):
    """Refuses a plan whose dense float grid exceeds the limit (GiB)."""
    dense = float(plan["dense_bytes"])
    if dense > limit_gib * GIB:
        nx, ny, nz = plan["dims"]
        raise ValueError(
            f"voxel size {voxel_size_text}: the cloud's box is {nx} x {ny} x {nz} voxels, "
            f"{dense / GIB:.3g} GiB as dense floats, over the limit of {limit_gib:.3g} GiB "
            f"(add-on preference 'Memory limit'); choose a larger voxel size")
