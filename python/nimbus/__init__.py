"""nimbus: procedural clouds and gases as OpenVDB volumes, and their renderer, from Python.

The same code as the ``nimbus`` program: ``generate`` makes the voxels ``nimbus generate`` makes,
``render`` the pixels ``nimbus render`` writes, ``read`` reads files through the same isolated
reader. Long calls release the GIL and stop on Ctrl+C (KeyboardInterrupt). Bad arguments raise
ValueError, failures at run time RuntimeError or OSError, each with the program's one-line message.

    >>> import nimbus
    >>> cloud = nimbus.generate("cumulus-humilis", seed=3)
    >>> cloud.density.shape, cloud.voxel_size          # NumPy float32 [x, y, z], metres
    >>> cloud.write("humilis.vdb")                    # what `nimbus generate -o` writes
    >>> image = nimbus.render([cloud], eye=(1500, -2500, 400), look_at=(0, 0, 1000), time_of_day=15)

World positions are in metres, in nimbus's one world: Z up, x east, y north (Blender's
convention). Volumes, ``render``'s camera, lamps and sun, and the program's flags all use it.
"""
from __future__ import annotations

import json
import math
import numbers
import os
import inspect
import re
import stat
from typing import Any, Callable, Iterable, Mapping, Optional, Sequence, Union

from . import _nimbus

__all__ = ["Volume", "VOXEL_SIZE_RANGE_M", "presets", "preset", "plan", "generate", "read", "render", "noise", "write_image", "read_image",
           "__version__"]
__version__ = _nimbus.__version__

# Foreign files are read by this program, in a process of its own (installed beside the core).
_nimbus._set_reader_program(os.path.join(os.path.dirname(os.path.abspath(__file__)), "nimbus-vdb-reader"))

Volume = _nimbus.Volume
Volume.__doc__ = """A density volume: a fog grid of voxels, its place in the world and its file metadata.

Made by ``generate``, ``read`` and ``Volume.from_array`` (it has no constructor of its own).

Attributes:
    density: NumPy float32 array indexed [x, y, z] (the order of OpenVDB's copyToArray), a view
        of the volume's own voxels (no copy; Fortran-ordered). Writable: edits change the volume.
    origin: index (i, j, k) of density[0, 0, 0]; its centre is at origin * voxel_size metres.
    voxel_size: edge of a voxel in metres (a 3-tuple if the voxels are not cubes).
    index_to_world: 4x4 matrix (rows) taking index (i, j, k, 1) to world metres; None for a frustum.
    up_axis: "z" (nimbus, Blender) or "y" (Houdini): which world axis points up.
    metadata: dict of the file-level metadata (preset, seed, time, up_axis, units, ...).
    extra_grids: names of the other grids it carries (a hot gas's "temperature").
"""

# The voxel sizes a Volume may have, in metres: the range generate takes (nimbus voxel-size range).
VOXEL_SIZE_RANGE_M = tuple(_nimbus._voxel_size_range())


def _volume_write(self: Volume, path: Union[str, os.PathLike], *, half_float: bool = True) -> None:
    """Write the volume as an OpenVDB fog volume, atomically, as ``nimbus generate`` does.

    half_float: store 16-bit floats (the program's default; ``nimbus generate --float`` is False).
    Raises ValueError for a NaN, infinite or negative density, OSError/RuntimeError when the file
    cannot be written.
    """
    _call(self._write, _path(path, "path"), _bool(half_float, "half_float"), flags={})


def _volume_from_array(array: Any, voxel_size: float, origin: Sequence[int] = (0, 0, 0), *,
                       up_axis: str = "z") -> Volume:
    """A volume from densities a user computed: ``array`` indexed [x, y, z] (3-D, any real dtype,
    copied once as float32), voxels of ``voxel_size`` metres (within VOXEL_SIZE_RANGE_M), element
    [0, 0, 0] at index ``origin``.

    Raises TypeError for an array that is not of real numbers; ValueError for a NaN, infinite,
    negative or float32-overflowing density (naming the element), a shape that is not 3-D, a voxel
    size out of range, or an origin beyond index +-2^30.
    """
    import numpy

    try:
        arr = numpy.asarray(array)
    except (ValueError, TypeError) as e:
        raise TypeError(f"array: cannot be read as an array of numbers ({_short(str(e))})") from None
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"array: expected real numbers, got dtype {arr.dtype}")
    if arr.ndim != 3:
        raise ValueError(f"array: must have 3 dimensions [x, y, z], got {arr.ndim}")
    if arr.dtype.kind == "f" and arr.dtype.itemsize > 4 and arr.size:
        big = numpy.abs(arr) > numpy.finfo(numpy.float32).max
        big &= numpy.isfinite(arr)
        if big.any():
            i, j, k = (int(n) for n in numpy.argwhere(big)[0])
            raise ValueError(f"array[{i}, {j}, {k}] is {float(arr[i, j, k]):g}, beyond float32's range "
                             f"(3.40282e+38): a density is stored as float32")
    if up_axis not in ("z", "y"):
        raise ValueError(f"up_axis: must be 'z' or 'y', got {_short(up_axis)}")
    return _call(_nimbus._from_array, arr, _number(voxel_size, "voxel_size"), _int3(origin, "origin"), up_axis, flags={})


def _volume_repr(self: Volume) -> str:
    shape = self.density.shape
    return (f"<nimbus.Volume {shape[0]}x{shape[1]}x{shape[2]} voxels of {self.voxel_size} m, origin {self.origin}, "
            f"{self.up_axis}-up, preset {self.metadata.get('preset', '')!r}>")


Volume.write = _volume_write
Volume.from_array = staticmethod(_volume_from_array)
Volume.__repr__ = _volume_repr


def presets() -> list[str]:
    """The names of the shipped presets, sorted (``nimbus presets``)."""
    return [name for name, _genus, _description in _nimbus._presets()]


def preset(name: str) -> dict:
    """A preset's parameters as ``nimbus presets show NAME`` prints them: {"cloud": {...}, ...}.

    Raises ValueError naming an unknown preset (and listing the known ones).
    """
    return json.loads(_call(_nimbus._preset_json, _text(name, "name"), flags={}))


def _sets(overrides: Optional[Mapping[str, Any]]) -> list[str]:
    """A dict of overrides as ``--set key=value`` texts (values as JSON: numbers, lists, strings)."""
    if overrides is None:
        return []
    if not isinstance(overrides, Mapping):
        raise TypeError(f"overrides: expected a dict of parameter names to values, got {_type_name(overrides)}")
    out = []
    for key, value in overrides.items():
        if not isinstance(key, str):
            raise TypeError(f"overrides: a key must be a string (e.g. 'coverage' or 'shapes.0.size'), got {_type_name(key)}")
        if not key or "\0" in key:
            raise ValueError(f"overrides: key {_short(key)} must be a non-empty string without NUL")
        try:
            text = json.dumps(value, allow_nan=False)
        except TypeError:
            raise TypeError(f"overrides: {key[:40]}: a value must be a number, string, bool or a list or dict "
                            f"of them, got {_type_name(value)}") from None
        except ValueError:
            raise ValueError(f"overrides: {key[:40]}: NaN and infinity are not parameter values") from None
        except RecursionError:
            raise ValueError(f"overrides: {key[:40]}: nested too deeply") from None
        out.append(f"{key}={text}")
    return out


def _coverage_map(value: Any) -> Any:
    """coverage_map as the module takes it: None, a PNG path, or (float32 bytes, width, height)."""
    if value is None:
        return None
    if isinstance(value, (str, bytes, os.PathLike)):
        return _path(value, "coverage_map")
    import numpy as np

    try:
        a = np.asarray(value)
    except (ValueError, TypeError):
        a = None
    if a is None or a.dtype.kind not in "fiub":
        raise TypeError(f"coverage_map: expected a PNG path or a 2-D array of numbers in [0, 1] (row 0 north), "
                        f"got {_type_name(value)}")
    if a.ndim != 2 or a.size == 0:
        raise ValueError(f"coverage_map: must be a 2-D array of numbers in [0, 1] (row 0 north), got shape {a.shape}")
    if a.shape[0] > 16384 or a.shape[1] > 16384:
        raise ValueError(f"coverage_map: {a.shape[1]}x{a.shape[0]} values, more than 16384 along an axis")
    with np.errstate(over="ignore", invalid="ignore"):
        a = np.ascontiguousarray(a, dtype=np.float32)
    return (a.tobytes(), int(a.shape[1]), int(a.shape[0]))


# The flags of `nimbus generate` that generate's arguments stand for (their errors name them).
_GENERATE_FLAGS = {"--preset": "preset", "--seed": "seed", "--voxel-size": "voxel_size", "--res": "res",
                   "--time": "time", "--set": "overrides", "--params": "params_file",
                   "--coverage-map": "coverage_map", "--size": "size"}


def _generate_request(preset: str, seed: Optional[int], voxel_size: Optional[float], res: Optional[int],
                      time: float, overrides: Optional[Mapping[str, Any]], params_file: Optional[str],
                      coverage_map: Any = None, size: float = 1.0) -> tuple:
    return (_text(preset, "preset"), None if seed is None else _int(seed, "seed", 0, 0xFFFFFFFF),
            None if voxel_size is None else _number(voxel_size, "voxel_size"),
            None if res is None else _int(res, "res", 1, 4096),
            _number(time, "time"), _sets(overrides), _number(size, "size"),
            "" if params_file is None else _path(params_file, "params_file"), _coverage_map(coverage_map))


def plan(preset: str, *, seed: Optional[int] = None, voxel_size: Optional[float] = None, res: Optional[int] = None,
         time: float = 0.0, overrides: Optional[Mapping[str, Any]] = None, params_file: Optional[str] = None,
         coverage_map: Any = None, size: float = 1.0) -> dict:
    """What ``generate`` would make, without making it (cheap): ``nimbus generate --plan-json``'s
    plan as a dict, with ``voxel_size`` (m), ``size`` (the size factor), ``time`` (s), ``dims``
    (voxels along x, y, z of the cloud's box), ``dense_bytes`` (that box as float32), ``bounds_m``
    ((x0, y0, z0), (x1, y1, z1)) voxel centres in metres and ``index_box`` (the same in voxels),
    None when empty, and ``optics``: the look ``render`` gives the cloud where no option says
    otherwise (``extinction_per_m``, ``albedo``, ``phase``: ``g_forward``, ``g_back``,
    ``forward_weight``).

    Raises ValueError exactly where ``generate`` would for its arguments.
    """
    request = _generate_request(preset, seed, voxel_size, res, time, overrides, params_file, coverage_map, size)
    d = json.loads(_call(_nimbus._plan, *request, flags=_GENERATE_FLAGS))
    d["dims"] = tuple(d["dims"])
    for key in ("bounds_m", "index_box"):
        if d[key] is not None:
            d[key] = tuple(tuple(corner) for corner in d[key])
    return d


def generate(preset: str, *, seed: Optional[int] = None, voxel_size: Optional[float] = None, res: Optional[int] = None,
             time: float = 0.0, overrides: Optional[Mapping[str, Any]] = None, params_file: Optional[str] = None,
             coverage_map: Any = None, size: float = 1.0,
             progress: Optional[Callable[[float], Any]] = None) -> Volume:
    """Generate a preset's cloud or gas at ``time`` seconds: the voxels ``nimbus generate`` makes for
    the same arguments (its file stores them as half floats unless ``--float``).

    seed: None = the preset's own (each preset file sets one: 3 for cumulus-humilis, 7 for
    cumulus-congestus); an integer in [0, 2^32).
    voxel_size: metres (None = the preset's); or res: voxels across the cloud's largest extent.
    overrides: ``--set`` as a dict, e.g. {"coverage": 0.7, "shapes.0.size": [700, 600, 350]}.
    params_file: a JSON file of overrides (``--params``).
    coverage_map: where clouds form (``--coverage-map``): a grey PNG path (red channel), or a 2-D
        array of values in [0, 1], row 0 the north edge, stretched over the field's area (or the
        preset's coverage_map_extent); 0 no cloud, 1 as without a map. docs/volume.md, Coverage maps.
    size: the size factor (``--size``, 0.01-100): the cloud this many times as large about its base
        centre, its noise with it, after the overrides; the preset's voxel size grows with it.
    progress: called now and then with the fraction done (0..1), on the calling thread; an
        exception it raises stops this call (and no other) and is raised here.

    Raises TypeError for an argument of the wrong type, ValueError for a bad value (an unknown
    preset or key, a voxel size whose box would not fit in memory), RuntimeError when the cloud
    has no voxel at this size, and KeyboardInterrupt on Ctrl+C (the work stops within a fraction of
    a second).
    """
    if progress is not None and not callable(progress):
        raise TypeError(f"progress: expected a callable (it is called with the fraction done), got {_type_name(progress)}")
    request = _generate_request(preset, seed, voxel_size, res, time, overrides, params_file, coverage_map, size)
    return _call(_nimbus._generate, *request, progress, flags=_GENERATE_FLAGS)


def read(path: Union[str, os.PathLike], *, grid: Optional[str] = None) -> Volume:
    """Read a float grid from an OpenVDB file: ``grid`` (default: "density", else the first float
    grid), its values as the file holds them (a ``nimbus noise`` field keeps its negative half;
    ``Volume.grid`` names the grid). Files nimbus wrote are checked against their seal; any other
    file is read by a separate program with a memory and time limit, so that a damaged or hostile
    file cannot crash Python. ``render`` reads negative values as 0, as ``nimbus render`` reads a
    file's, and says so in a warning; ``Volume.write`` refuses them (a file nimbus writes holds a
    density).

    Raises FileNotFoundError/OSError for a missing, unreadable or non-regular path (a directory, a
    FIFO), ValueError for an unknown grid, RuntimeError for a file that is not a readable fog
    volume (each naming the file).
    """
    p = _regular_file(_path(path, "path"), "VDB")
    return _call(_nimbus._read, p, None if grid is None else _text(grid, "grid"), flags={"--grid": "grid"})


def _regular_file(path: str, kind: str) -> str:
    """``path`` if it names a regular file; else the OSError that says what it is (before any open,
    so that a FIFO cannot block the call)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise FileNotFoundError(2, "no such file", path) from None
    except OSError as e:
        raise OSError(e.errno, f"cannot be read ({e.strerror})", path) from None
    if stat.S_ISDIR(mode):
        raise IsADirectoryError(21, f"a directory, not a {kind} file", path)
    if not stat.S_ISREG(mode):
        what = "a FIFO" if stat.S_ISFIFO(mode) else "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else \
            "a socket" if stat.S_ISSOCK(mode) else "not a regular file"
        raise OSError(22, f"{what}, not a {kind} file", path)
    return path


# render's options: nimbus render's flags by name (dashes as underscores), and whether each takes
# a value (a switch takes True or False).
_RENDER_FLAGS = {flag: takes_value for flag, takes_value, _default, _help in _nimbus._render_flags()}
_RENDER_NAMES = {flag: flag[2:].replace("-", "_") for flag in _RENDER_FLAGS} | {"--preset": "preset"}
_RENDER_OWN = ("--eye", "--look-at", "--up", "--fov", "--res", "--sun", "--scene")


def _flag_value(name: str, value: Any, depth: int = 0) -> str:
    if isinstance(value, str):
        if "\0" in value:
            raise ValueError(f"{name}: must not contain a NUL character")
        return value
    if isinstance(value, bool):
        raise TypeError(f"{name}: takes a value (a number, a text or a sequence of numbers), not True or False")
    if isinstance(value, numbers.Integral):
        return str(int(value)) if abs(int(value)) < 10 ** 18 else repr(_number(value, name))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if depth == 0 and isinstance(value, Iterable) and not isinstance(value, (bytes, Mapping)):
        return ",".join(_flag_value(name, v, 1) for v in _sequence(value, name))
    raise TypeError(f"{name}: expected a number, a text or a sequence of numbers, got {_type_name(value)}")


def _render_option(name: str, value: Any) -> list[str]:
    if not isinstance(name, str) or not name.isidentifier():
        raise TypeError(f"render: options are given by name, got {_short(name)}")
    flag = "--" + name.replace("_", "-")
    if flag not in _RENDER_FLAGS or flag in _RENDER_OWN:
        raise ValueError(f"{name}: not an option of render (its options are nimbus render's flags, "
                         f"e.g. slices=256 for --slices 256; see nimbus render --help)")
    if value is None:
        return []
    if not _RENDER_FLAGS[flag]:  # a switch
        return [flag] if _bool(value, name) else []
    if isinstance(value, (list, tuple)) and value and isinstance(value[0], (list, tuple, str)):
        # a repeatable flag: lamp=[(0, 1, 0), (5, 1, 0)], preset=["a", "b"]
        return [f"{flag}={_flag_value(f'{name}[{i}]', v)}" for i, v in enumerate(_sequence(value, name))]
    return [f"{flag}={_flag_value(name, value)}"]


def _render_args(paths: list[str], scene: str, eye, look_at, up, fov, res, sun, options: Mapping[str, Any]) -> list[str]:
    # Every value follows its flag after "=", and the paths come after "--": no value or path
    # (a file named "--help") can be read as a flag.
    args = ["--scene=" + _text(scene, "scene")]
    for name, flag, value in (("eye", "--eye", eye), ("look_at", "--look-at", look_at), ("up", "--up", up),
                              ("fov", "--fov", fov), ("sun", "--sun", sun)):
        if value is not None:
            args.append(f"{flag}={_flag_value(name, value)}")
    if res is not None:
        items = _sequence(res, "res")
        if len(items) != 2:
            raise ValueError(f"res: must be (width, height), got {len(items)} numbers")
        w, h = (_int(v, f"res[{i}]") for i, v in enumerate(items))
        args.append(f"--res={w}x{h}")
    for name, value in options.items():
        args += _render_option(name, value)
    return args + ["--"] + list(paths)


def render(volumes_or_paths: Union[Volume, str, os.PathLike, Iterable[Union[Volume, str, os.PathLike]]], *,
           scene: str = "sky", eye: Optional[Sequence[float]] = None, look_at: Optional[Sequence[float]] = None,
           up: Optional[Sequence[float]] = None, fov: Optional[float] = None, res: Optional[Sequence[int]] = None,
           sun: Optional[Sequence[float]] = None, **options: Any):
    """Render clouds as ``nimbus render`` does, headless (EGL; Mesa's llvmpipe where there is no GPU):
    the same pixels as the program's EXR for the same flags, as a NumPy float32 array (height,
    width, 4): linear radiance (W sr^-1 m^-2), premultiplied RGBA, row 0 at the top.

    volumes_or_paths: Volumes and VDB file paths (one, or a list), in the order given. A Volume is
    rendered from memory, as the cloud its file (written in float) would be: no file is written;
    its negative values (a read noise grid's) are read as 0 with a warning, as a file's are.
    ``preset="name"`` (or a list) in options generates presets as ``--preset`` does.
    scene: "sky" (ground, sun, haze, physical sky), "none" (clouds alone) or another scene
    (``nimbus render --help``). eye, look_at, up: metres, Z up (x east, y north), as the volumes;
    without eye and look_at the camera frames the clouds. sun: the direction towards the sun, Z up
    (or ``sun_elevation=35, sun_azimuth=135`` in degrees, or ``time_of_day=15`` with ``latitude``
    and ``day_of_year``, as the program's flags). fov: degrees (horizontal). res: (width, height).
    up, fov and res left None take the program's defaults, so that a call and ``nimbus render``
    with the same flags give the same picture: the scene's camera (1280x720, Z up), or with
    scene="none" vdb_render's (512x512 at 44.8 degrees).
    options: the program's other flags by name, dashes as underscores: method="pathtrace",
    slices=256, spp=64, cloud_extinction=0.04, no_jitter=True, ms_photons=1 << 20, time=12.0 ...
    A switch takes True or False; every other option a number, a text or a sequence of numbers.

    Raises TypeError for an argument of the wrong type, ValueError for a bad or unknown option
    (named as here), RuntimeError when rendering fails (no OpenGL, a file that cannot be read),
    KeyboardInterrupt on Ctrl+C.
    """
    for name in ("output", "o", "preview", "exposure", "view_state", "frames"):
        if name in options:
            raise ValueError(f"{name}: render returns one image in memory; write it yourself "
                             f"(and call render once per time for a sequence)")
    single = isinstance(volumes_or_paths, (Volume, str, bytes, os.PathLike))
    if single:
        items = [volumes_or_paths]
    elif isinstance(volumes_or_paths, Iterable):
        items = _sequence(volumes_or_paths, "volumes_or_paths")
    else:
        raise TypeError(f"volumes_or_paths: expected a Volume, a VDB path or a list of them, "
                        f"got {_type_name(volumes_or_paths)}")
    args = _render_args([], scene, eye, look_at, up, fov, res, sun, options)  # every option checked first
    # Volumes are rendered from memory, each as the file it would be written to (in float) would
    # be; paths are read as the program reads them. Both keep the order given.
    paths, volumes = [], []
    for i, item in enumerate(items):
        argument = "volumes_or_paths" if single else f"volumes_or_paths[{i}]"
        if isinstance(item, Volume):
            volumes.append((len(paths), item, f"{argument} (a Volume)"))
        elif isinstance(item, (str, bytes, os.PathLike)):
            paths.append(_regular_file(_path(item, argument), "VDB"))
        else:
            raise TypeError(f"{argument}: {_type_name(item)} is neither a Volume nor a path")
    image, warnings_said = _call(_nimbus._render, args + paths, volumes, flags=_RENDER_NAMES)
    if warnings_said:
        import warnings

        for text in warnings_said:
            warnings.warn(text, stacklevel=2)
    return image


# render's settings: the one table of nimbus's render settings (render_settings.hpp in the
# library), which the program's flags and the viewer's state read too. Each that render takes is
# a typed keyword argument of its signature, with the table's default (None where the table
# says the default in words: it depends on the rest of the render), and a line of its docstring.
_RENDER_SETTINGS = [dict(s, name=s["flag"].replace("-", "_")) for s in _nimbus._render_settings()
                    if s["flag"] and "--" + s["flag"] in _RENDER_FLAGS and "--" + s["flag"] not in _RENDER_OWN]


def _setting_default(s: Mapping[str, Any]) -> Optional[float]:
    if s["default_text"]:
        return None
    return int(s["default"]) if s["integer"] else s["default"]


def _render_signature(fn: Callable) -> inspect.Signature:
    sig = inspect.signature(fn)
    params = [p for p in sig.parameters.values() if p.kind != p.VAR_KEYWORD]
    for s in _RENDER_SETTINGS:
        kind = int if s["integer"] else float
        params.append(inspect.Parameter(s["name"], inspect.Parameter.KEYWORD_ONLY, default=_setting_default(s),
                                        annotation=Optional[kind] if s["default_text"] else kind))
    return sig.replace(parameters=params + [sig.parameters["options"]])


def _settings_doc() -> str:
    lines = ["", "    Settings, from the one table the program's flags and the viewer's state share:"]
    for s in _RENDER_SETTINGS:
        value = _setting_default(s)
        default = s["default_text"] or (str(value) if s["integer"] else f"{value:g}")
        lines.append(f"    {s['name']}: {s['help']}, {s['range']}; default {default}.")
    return "\n".join(lines) + "\n"


render.__signature__ = _render_signature(render)
render.__doc__ = (render.__doc__ or "") + _settings_doc()

def noise(kind: str, shape: Sequence[int], *, frequency: float = 1.0, fractal: str = "fbm", octaves: int = 6,
          seed: int = 0, time: Optional[float] = None, lacunarity: float = 2.0, gain: float = 0.5, period: int = 0,
          projected: bool = False, spacing: Optional[float] = None):
    """Sample a noise field (``nimbus noise``) on a grid: a NumPy float32 array of ``shape`` (2 or 3
    sizes) indexed [x, y(, z)], sample (i, j, k) at (i, j, k) * spacing input units; spacing
    defaults to 1 / max(shape), so the longest axis spans [0, 1) as the program's cube does.

    kind: value, gradient, wavelet or worley. fractal: none, fbm, turbulence or ridged (octaves
    must be 1 with none). frequency: lattice cycles per input unit, first octave. time: animation
    time in lattice units (None: not animated). period: integer period in lattice units (0: none).
    Raises TypeError for an argument of the wrong type, ValueError for a bad value, and
    KeyboardInterrupt on Ctrl+C (polled every few thousand samples).
    """
    dims = _ints(shape, "shape")
    if len(dims) not in (2, 3):
        raise ValueError(f"shape: must have 2 or 3 sizes, got {len(dims)}")
    full = dims + [1] * (3 - len(dims))
    for i, n in enumerate(full):
        if not 1 <= n <= 4096:
            raise ValueError(f"shape: every size must be in [1, 4096], got {n}")
    step = 1.0 / max(full) if spacing is None else _number(spacing, "spacing")
    out = _call(_nimbus._noise, _text(kind, "kind"), full, _number(frequency, "frequency"), _text(fractal, "fractal"),
                _int(octaves, "octaves"), _int(seed, "seed", 0, 0xFFFFFFFF), None if time is None else _number(time, "time"),
                _number(lacunarity, "lacunarity"), _number(gain, "gain"), _int(period, "period"),
                _bool(projected, "projected"), step, flags=_NOISE_FLAGS)
    return out if len(dims) == 3 else out[:, :, 0]


# The flags of `nimbus noise` that noise's arguments stand for.
_NOISE_FLAGS = {"--kind": "kind", "--frequency": "frequency", "--fractal": "fractal", "--octaves": "octaves",
                "--seed": "seed", "--time": "time", "--lacunarity": "lacunarity", "--gain": "gain",
                "--period": "period", "--projected": "projected", "--spacing": "spacing"}


def write_image(path: Union[str, os.PathLike], image: Any, *, preview: Optional[Union[str, os.PathLike]] = None,
                exposure: Optional[float] = None, metadata: Optional[Mapping[str, str]] = None) -> None:
    """Write a render as ``nimbus render`` writes its files: ``path`` a linear half-float OpenEXR
    (values above 65504 clamp) and, if given, ``preview`` a filmic (AgX) sRGB PNG, exposed by
    ``exposure`` stops (None: automatic). Both are written together and atomically.

    Raises TypeError for an image that is not an array of real numbers; ValueError for one that is
    not (height, width, 4) finite, non-negative numbers, a name that does not end in .exr/.png, or
    a bad exposure; OSError/RuntimeError when writing fails.
    """
    import numpy as np

    exr = _path(path, "path")
    if not exr.lower().endswith(".exr"):
        raise ValueError(f"path: '{_short(exr)}' must end in .exr (the image is a linear OpenEXR; a PNG: preview=)")
    png = "" if preview is None else _path(preview, "preview")
    if png and not png.lower().endswith(".png"):
        raise ValueError(f"preview: '{_short(png)}' must end in .png")
    if metadata is not None and not isinstance(metadata, Mapping):
        raise TypeError(f"metadata: expected a dict of strings, got {_type_name(metadata)}")
    meta = {} if metadata is None else {_text(k, "metadata key"): _text(v, f"metadata[{_short(k)}]")
                                        for k, v in metadata.items()}
    try:
        pixels = np.asarray(image)
    except (ValueError, TypeError):
        pixels = None
    if pixels is None or pixels.dtype.kind not in "biuf":
        raise TypeError(f"image: expected a (height, width, 4) array of real numbers, got {_type_name(image)}")
    if pixels.ndim != 3 or pixels.shape[2] != 4 or pixels.shape[0] < 1 or pixels.shape[1] < 1:
        raise ValueError(f"image: must be a (height, width, 4) array of RGBA numbers, as render returns; "
                         f"got shape {pixels.shape}")
    _call(_nimbus._write_image, exr, png, pixels, None if exposure is None else _number(exposure, "exposure"), meta,
          flags={"--exposure": "exposure", "--preview": "preview", "-o": "path"})


def read_image(path: Union[str, os.PathLike]) -> tuple:
    """Read an OpenEXR image: ((height, width, 4) float32 RGBA, row 0 at the top; its header's text
    attributes as a dict). Raises FileNotFoundError or OSError for a missing or non-regular path (a
    FIFO is refused, never opened), RuntimeError for a file that is not a readable EXR, naming it."""
    return _call(_nimbus._read_image, _regular_file(_path(path, "path"), "EXR"), flags={})


# Argument checks: each names the argument. A wrong type is a TypeError naming the type expected;
# a value of the right type out of its range is a ValueError; numbers print as numbers (%g), and
# no message repeats a whole argument.
def _type_name(value: Any) -> str:
    return type(value).__name__


def _text(value: Any, name: str) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a string, got {_type_name(value)}")
    if "\0" in value:
        raise ValueError(f"{name}: must not contain a NUL character")
    return value


def _path(value: Any, name: str) -> str:
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if isinstance(value, bytes):
        value = os.fsdecode(value)
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a path (str or os.PathLike), got {_type_name(value)}")
    text = _text(value, name)
    if not text:
        raise ValueError(f"{name}: the path is empty")
    return text


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name}: expected a number, got {_type_name(value)}")
    try:
        v = float(value)
    except OverflowError:  # an int beyond the float range
        raise ValueError(f"{name}: {_short(value)} is beyond the range of a float") from None
    if not math.isfinite(v):
        raise ValueError(f"{name}: must be finite, got {v:g}")
    return v


def _int(value: Any, name: str, lo: int = -(1 << 31), hi: int = (1 << 31) - 1) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name}: expected an integer, got {_type_name(value)}")
    v = int(value)
    if not lo <= v <= hi:
        raise ValueError(f"{name}: must be an integer in [{lo}, {hi}], got {_short(v)}")
    return v


def _short(value: Any) -> str:
    """A value as a message shows it: numbers as %g, anything else cut to 40 characters."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        text = str(int(value)) if abs(int(value)) < 10 ** 15 else f"{float(value):g}" if abs(int(value)) < 10 ** 300 else "a huge integer"
    elif isinstance(value, numbers.Real) and not isinstance(value, bool):
        text = f"{float(value):g}"
    else:
        text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _sequence(values: Any, name: str) -> list:
    if isinstance(values, (str, bytes)) or not isinstance(values, Iterable):
        raise TypeError(f"{name}: expected a sequence, got {_type_name(values)}")
    items = list(values)
    if len(items) > 1024:
        raise ValueError(f"{name}: {len(items)} items, more than any argument takes")
    return items


def _ints(values: Any, name: str) -> list[int]:
    return [_int(v, f"{name}[{i}]") for i, v in enumerate(_sequence(values, name))]


def _int3(values: Any, name: str) -> list[int]:
    items = _ints(values, name)
    if len(items) != 3:
        raise ValueError(f"{name}: must have 3 integers (i, j, k), got {len(items)}")
    return items


def _bool(value: Any, name: str) -> bool:
    if isinstance(value, bool) or _type_name(value) == "bool_":  # NumPy's bool too
        return bool(value)
    if isinstance(value, numbers.Integral) and int(value) in (0, 1):
        return bool(value)
    raise TypeError(f"{name}: expected True or False, got {_type_name(value)}")


# The program's words for a call's arguments, rewritten as Python's: its flags (--voxel-size) as
# the argument names (voxel_size: `flags` names those that differ, such as --set for overrides),
# and the temporary files render writes for Volumes as the arguments they came from. Applied to
# every error the core raises, so that no message names a flag or a temporary file.
_FLAG = re.compile(r"(?<![\w.-])--[a-z][a-z0-9-]*")


def _python_words(message: str, flags: Mapping[str, str], paths: Mapping[str, str]) -> str:
    for path, argument in paths.items():
        message = message.replace(path, argument)
    return _FLAG.sub(lambda m: flags.get(m.group(0), m.group(0)[2:].replace("-", "_")), message)


def _call(function: Callable, *args: Any, flags: Mapping[str, str], paths: Mapping[str, str] = {}) -> Any:
    try:
        return function(*args)
    except (ValueError, RuntimeError, OSError) as e:
        text = str(e)
        said = _python_words(text, flags, paths)
        if said == text:
            raise
        error = type(e)(said) if not isinstance(e, OSError) or e.errno is None else type(e)(e.errno, said)
        raise error from None
