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
import tempfile
from typing import Any, Callable, Iterable, Mapping, Optional, Sequence, Union

from . import _nimbus

__all__ = ["Volume", "presets", "preset", "plan", "generate", "read", "render", "noise", "write_image", "read_image",
           "__version__"]
__version__ = _nimbus.__version__

# Foreign files are read by this program, in a process of its own (installed beside the core).
_nimbus._set_reader_program(os.path.join(os.path.dirname(os.path.abspath(__file__)), "nimbus-vdb-reader"))

Volume = _nimbus.Volume
Volume.__doc__ = """A density volume: a fog grid of voxels, its place in the world and its file metadata.

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


def _volume_write(self: Volume, path: Union[str, os.PathLike], *, half_float: bool = True) -> None:
    """Write the volume as an OpenVDB fog volume, atomically, as ``nimbus generate`` does.

    half_float: store 16-bit floats (the program's default; ``nimbus generate --float`` is False).
    Raises ValueError for a NaN, infinite or negative density, OSError/RuntimeError when the file
    cannot be written.
    """
    self._write(_path(path, "path"), bool(half_float))


def _volume_from_array(array: Any, voxel_size: float, origin: Sequence[int] = (0, 0, 0), *,
                       up_axis: str = "z") -> Volume:
    """A volume from densities a user computed: ``array`` indexed [x, y, z] (3-D, any real dtype,
    copied once as float32), voxels of ``voxel_size`` metres, element [0, 0, 0] at index ``origin``.

    Raises ValueError for a NaN, infinite or negative density (naming the element), a shape that is
    not 3-D, a voxel size that is not finite and > 0, or an origin beyond index +-2^30.
    """
    import numpy

    arr = numpy.asarray(array)
    if arr.dtype.kind not in "biuf":
        raise ValueError(f"array: dtype {arr.dtype} is not a real number type")
    return _nimbus._from_array(arr, _number(voxel_size, "voxel_size"), _int3(origin, "origin"), str(up_axis))


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
    return json.loads(_nimbus._preset_json(_text(name, "name")))


def _sets(overrides: Optional[Mapping[str, Any]]) -> list[str]:
    """A dict of overrides as ``--set key=value`` texts (values as JSON: numbers, lists, strings)."""
    if overrides is None:
        return []
    if not isinstance(overrides, Mapping):
        raise ValueError(f"overrides: must be a dict of parameter names to values, got {type(overrides).__name__}")
    out = []
    for key, value in overrides.items():
        if not isinstance(key, str) or not key:
            raise ValueError(f"overrides: key {key!r} must be a non-empty string (e.g. 'coverage' or 'shapes.0.size')")
        try:
            text = json.dumps(value, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise ValueError(f"overrides: {key}: {e}") from None
        out.append(f"{key}={text}")
    return out


def _coverage_map(value: Any) -> Any:
    """coverage_map as the module takes it: None, a PNG path, or (float32 bytes, width, height)."""
    if value is None:
        return None
    if isinstance(value, (str, os.PathLike)):
        return _path(value, "coverage_map")
    import numpy as np

    a = np.asarray(value)
    if a.ndim != 2 or a.dtype.kind not in "fiu":
        raise ValueError(f"coverage_map: must be a PNG path or a 2-D array of numbers in [0, 1] (row 0 north), "
                         f"got {type(value).__name__} of shape {getattr(a, 'shape', None)}")
    a = np.ascontiguousarray(a, dtype=np.float32)
    return (a.tobytes(), int(a.shape[1]), int(a.shape[0]))


def _generate_request(preset: str, seed: Optional[int], voxel_size: Optional[float], res: Optional[int],
                      time: float, overrides: Optional[Mapping[str, Any]], params_file: Optional[str],
                      coverage_map: Any = None) -> tuple:
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)
                             or not 0 <= int(seed) <= 0xFFFFFFFF):
        raise ValueError(f"seed: must be an integer in [0, 4294967295], got {seed!r}")
    if res is not None and (isinstance(res, bool) or not isinstance(res, numbers.Integral)
                            or not 1 <= int(res) <= 4096):
        raise ValueError(f"res: must be an integer in [1, 4096], got {res!r}")
    return (_text(preset, "preset"), None if seed is None else int(seed),
            None if voxel_size is None else _number(voxel_size, "voxel_size"), None if res is None else int(res),
            _number(time, "time"), _sets(overrides), "" if params_file is None else _path(params_file, "params_file"),
            _coverage_map(coverage_map))


def plan(preset: str, *, seed: Optional[int] = None, voxel_size: Optional[float] = None, res: Optional[int] = None,
         time: float = 0.0, overrides: Optional[Mapping[str, Any]] = None, params_file: Optional[str] = None,
         coverage_map: Any = None) -> dict:
    """What ``generate`` would make, without making it (cheap): a dict with ``voxel_size`` (m),
    ``dims`` (voxels along x, y, z of the cloud's box), ``dense_bytes`` (that box as float32) and
    ``bounds_m`` ((x0, y0, z0), (x1, y1, z1)) voxel centres in metres, None when empty.

    Raises ValueError exactly where ``generate`` would for its arguments.
    """
    return _nimbus._plan(*_generate_request(preset, seed, voxel_size, res, time, overrides, params_file, coverage_map))


def generate(preset: str, *, seed: Optional[int] = None, voxel_size: Optional[float] = None, res: Optional[int] = None,
             time: float = 0.0, overrides: Optional[Mapping[str, Any]] = None, params_file: Optional[str] = None,
             coverage_map: Any = None, progress: Optional[Callable[[float], Any]] = None) -> Volume:
    """Generate a preset's cloud or gas at ``time`` seconds: the voxels ``nimbus generate`` makes for
    the same arguments (its file stores them as half floats unless ``--float``).

    seed: None = the preset's own (1 for every shipped preset); an integer in [0, 2^32).
    voxel_size: metres (None = the preset's); or res: voxels across the cloud's largest extent.
    overrides: ``--set`` as a dict, e.g. {"coverage": 0.7, "shapes.0.size": [700, 600, 350]}.
    params_file: a JSON file of overrides (``--params``).
    coverage_map: where clouds form (``--coverage-map``): a grey PNG path (red channel), or a 2-D
        array of values in [0, 1], row 0 the north edge, stretched over the field's area (or the
        preset's coverage_map_extent); 0 no cloud, 1 as without a map. docs/volume.md, Coverage maps.
    progress: called now and then with the fraction done (0..1), on the calling thread.

    Raises ValueError for bad arguments (an unknown preset or key, a bad value, a voxel size whose
    box would not fit in memory), RuntimeError when the cloud has no voxel at this size, and
    KeyboardInterrupt on Ctrl+C (the work stops within a fraction of a second).
    """
    if progress is not None and not callable(progress):
        raise ValueError("progress: must be callable (it is called with the fraction done)")
    return _nimbus._generate(*_generate_request(preset, seed, voxel_size, res, time, overrides, params_file, coverage_map),
                             progress)


def read(path: Union[str, os.PathLike], *, grid: Optional[str] = None) -> Volume:
    """Read a fog volume from an OpenVDB file: ``grid`` (default: "density", else the first float
    grid). Files nimbus wrote are checked against their seal; any other file is read by a separate
    program with a memory and time limit, so that a damaged or hostile file cannot crash Python.
    Negative values (which a density cannot hold) are read as 0, as ``nimbus render`` reads them.

    Raises FileNotFoundError/OSError for a missing or unreadable path, ValueError for an unknown grid,
    RuntimeError for a file that is not a readable fog volume (each naming the file).
    """
    p = _path(path, "path")
    if not os.path.exists(p):
        raise FileNotFoundError(2, "no such file", p)
    if os.path.isdir(p):
        raise IsADirectoryError(21, "a directory, not a VDB file", p)
    volume, negatives = _nimbus._read(p, None if grid is None else _text(grid, "grid"))
    if negatives:
        import warnings

        warnings.warn(f"{p}: {negatives} negative values read as 0 (a density cannot be negative)", stacklevel=2)
    return volume


_RENDER_FLAGS = frozenset(_nimbus._render_flags())


def _flag_value(name: str, value: Any) -> str:
    if isinstance(value, str):
        return value
    if isinstance(value, (bool,)):
        raise ValueError(f"{name}: True/False is only for switches")
    if isinstance(value, numbers.Real):
        return repr(float(value)) if isinstance(value, float) else str(int(value))
    try:
        items = list(value)
    except TypeError:
        raise ValueError(f"{name}: {value!r} is not a number, a text or a sequence of numbers") from None
    return ",".join(_flag_value(name, v) for v in items)


def _render_args(paths: list[str], scene: str, eye, look_at, up, fov, res, sun, options: Mapping[str, Any]) -> list[str]:
    args = list(paths) + ["--scene", _text(scene, "scene")]
    if eye is not None:
        args += ["--eye", _flag_value("eye", eye)]
    if look_at is not None:
        args += ["--look-at", _flag_value("look_at", look_at)]
    if up is not None:
        args += ["--up", _flag_value("up", up)]
    if fov is not None:
        args += ["--fov", _flag_value("fov", fov)]
    if res is not None:
        try:
            w, h = res
        except (TypeError, ValueError):
            raise ValueError(f"res: must be (width, height), got {res!r}") from None
        args += ["--res", f"{_flag_value('res', w)}x{_flag_value('res', h)}"]
    if sun is not None:
        args += ["--sun", _flag_value("sun", sun)]
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        if flag not in _RENDER_FLAGS or flag in ("--eye", "--look-at", "--up", "--fov", "--res", "--sun", "--scene"):
            raise ValueError(f"{name}: not an option of render (its options are nimbus render's flags, "
                             f"e.g. slices=256 for --slices 256; see nimbus render --help)")
        if value is None or value is False:
            continue
        if value is True:
            args.append(flag)
        elif isinstance(value, (list, tuple)) and value and isinstance(value[0], (list, tuple, str)):
            for v in value:  # a repeatable flag: lamp=[(0, 1, 0), (5, 1, 0)], preset=["a", "b"]
                args += [flag, _flag_value(name, v)]
        else:
            args += [flag, _flag_value(name, value)]
    return args


def render(volumes_or_paths: Union[Volume, str, os.PathLike, Iterable[Union[Volume, str, os.PathLike]]], *,
           scene: str = "sky", eye: Optional[Sequence[float]] = None, look_at: Optional[Sequence[float]] = None,
           up: Optional[Sequence[float]] = (0, 0, 1), fov: Optional[float] = 45, res: Optional[Sequence[int]] = (640, 360),
           sun: Optional[Sequence[float]] = None, **options: Any):
    """Render clouds as ``nimbus render`` does, headless (EGL; Mesa's llvmpipe where there is no GPU):
    the same pixels as the program's EXR for the same flags, as a NumPy float32 array (height,
    width, 4): linear radiance (W sr^-1 m^-2), premultiplied RGBA, row 0 at the top.

    volumes_or_paths: Volumes and VDB file paths (one, or a list). ``preset="name"`` (or a list)
    in options generates presets as ``--preset`` does.
    scene: "sky" (ground, sun, haze, physical sky), "none" (clouds alone) or another scene
    (``nimbus render --help``). eye, look_at, up: metres, Z up (x east, y north), as the volumes;
    without eye and look_at the camera frames the clouds. sun: the direction towards the sun, Z up
    (or ``sun_elevation=35, sun_azimuth=135`` in degrees, or ``time_of_day=15`` with ``latitude``
    and ``day_of_year``, as the program's flags). fov: degrees (horizontal). res: (width, height).
    options: the program's other flags by name, dashes as underscores: method="pathtrace",
    slices=256, spp=64, cloud_extinction=0.04, no_jitter=True, ms_photons=1 << 20, time=12.0 ...

    Raises ValueError for a bad or unknown option (the program's message), RuntimeError when
    rendering fails (no OpenGL, a file that cannot be read), KeyboardInterrupt on Ctrl+C.
    """
    for name in ("output", "o", "preview", "exposure", "view_state", "frames"):
        if name in options:
            raise ValueError(f"{name}: render returns one image in memory; write it yourself "
                             f"(and call render once per time for a sequence)")
    items = [volumes_or_paths] if isinstance(volumes_or_paths, (Volume, str, os.PathLike)) else list(volumes_or_paths)
    with tempfile.TemporaryDirectory(prefix="nimbus-render-") as tmp:
        paths = []
        for i, item in enumerate(items):
            if isinstance(item, Volume):
                path = os.path.join(tmp, f"volume-{i}.vdb")
                item.write(path, half_float=False)  # float: the very voxels, sealed, read back in-process
                paths.append(path)
            elif isinstance(item, (str, os.PathLike)):
                paths.append(_path(item, f"volumes_or_paths[{i}]"))
            else:
                raise ValueError(f"volumes_or_paths[{i}]: {type(item).__name__} is neither a Volume nor a path")
        return _nimbus._render(_render_args(paths, scene, eye, look_at, up, fov, res, sun, options))


def noise(kind: str, shape: Sequence[int], *, frequency: float = 1.0, fractal: str = "fbm", octaves: int = 6,
          seed: int = 0, time: Optional[float] = None, lacunarity: float = 2.0, gain: float = 0.5, period: int = 0,
          projected: bool = False, spacing: Optional[float] = None):
    """Sample a noise field (``nimbus noise``) on a grid: a NumPy float32 array of ``shape`` (2 or 3
    sizes) indexed [x, y(, z)], sample (i, j, k) at (i, j, k) * spacing input units; spacing
    defaults to 1 / max(shape), so the longest axis spans [0, 1) as the program's cube does.

    kind: value, gradient, wavelet or worley. fractal: none, fbm, turbulence or ridged (octaves
    must be 1 with none). frequency: lattice cycles per input unit, first octave. time: animation
    time in lattice units (None: not animated). period: integer period in lattice units (0: none).
    Raises ValueError for a bad argument (the program's message).
    """
    dims = _ints(shape, "shape")
    if len(dims) not in (2, 3):
        raise ValueError(f"shape: must have 2 or 3 sizes, got {len(dims)}")
    full = dims + [1] * (3 - len(dims))
    step = 1.0 / max(full) if spacing is None else _number(spacing, "spacing")
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= int(seed) <= 0xFFFFFFFF:
        raise ValueError(f"seed: must be an integer in [0, 4294967295], got {seed!r}")
    out = _nimbus._noise(_text(kind, "kind"), full, _number(frequency, "frequency"), _text(fractal, "fractal"),
                         _int(octaves, "octaves"), int(seed), None if time is None else _number(time, "time"),
                         _number(lacunarity, "lacunarity"), _number(gain, "gain"), _int(period, "period"),
                         bool(projected), step)
    return out if len(dims) == 3 else out[:, :, 0]


def write_image(path: Union[str, os.PathLike], image: Any, *, preview: Optional[Union[str, os.PathLike]] = None,
                exposure: Optional[float] = None, metadata: Optional[Mapping[str, str]] = None) -> None:
    """Write a render as ``nimbus render`` writes its files: ``path`` a linear half-float OpenEXR
    (values above 65504 clamp) and, if given, ``preview`` a filmic (AgX) sRGB PNG, exposed by
    ``exposure`` stops (None: automatic). Both are written together and atomically.

    Raises ValueError for an image that is not (height, width, 4) finite, non-negative numbers,
    a name that does not end in .exr/.png, or a bad exposure; OSError/RuntimeError when writing fails.
    """
    exr = _path(path, "path")
    if not exr.lower().endswith(".exr"):
        raise ValueError(f"path: '{exr}' must end in .exr (the image is a linear OpenEXR; a PNG: preview=)")
    png = "" if preview is None else _path(preview, "preview")
    if png and not png.lower().endswith(".png"):
        raise ValueError(f"preview: '{png}' must end in .png")
    meta = {} if metadata is None else {_text(k, "metadata key"): _text(v, f"metadata[{k}]") for k, v in metadata.items()}
    _nimbus._write_image(exr, png, image, None if exposure is None else _number(exposure, "exposure"), meta)


def read_image(path: Union[str, os.PathLike]) -> tuple:
    """Read an OpenEXR image: ((height, width, 4) float32 RGBA, row 0 at the top; its header's text
    attributes as a dict). Raises FileNotFoundError or RuntimeError naming the file."""
    p = _path(path, "path")
    if not os.path.exists(p):
        raise FileNotFoundError(2, "no such file", p)
    return _nimbus._read_image(p)


# Argument checks: each names the argument, as the program's messages name the flag.
def _text(value: Any, name: str) -> str:
    if not isinstance(value, str):
        raise ValueError(f"{name}: must be a string, got {type(value).__name__}")
    if "\0" in value:
        raise ValueError(f"{name}: must not contain a NUL character")
    return value


def _path(value: Any, name: str) -> str:
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if isinstance(value, bytes):
        value = os.fsdecode(value)
    text = _text(value, name)
    if not text:
        raise ValueError(f"{name}: the path is empty")
    return text


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name}: must be a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name}: must be finite, got {v}")
    return v


def _int(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ValueError(f"{name}: must be an integer, got {value!r}")
    v = int(value)
    if not -(1 << 31) <= v < (1 << 31):
        raise ValueError(f"{name}: {v} is out of range")
    return v


def _ints(values: Any, name: str) -> list[int]:
    try:
        items = list(values)
    except TypeError:
        raise ValueError(f"{name}: must be a sequence of integers, got {values!r}") from None
    return [_int(v, f"{name}[{i}]") for i, v in enumerate(items)]


def _int3(values: Any, name: str) -> list[int]:
    items = _ints(values, name)
    if len(items) != 3:
        raise ValueError(f"{name}: must have 3 integers (i, j, k), got {len(items)}")
    return items
