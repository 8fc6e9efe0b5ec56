# Property tests of the module's argument handling (Hypothesis, Debian's python3-hypothesis):
# generated arrays (dtypes, shapes, strides, NaN and infinities, huge values), paths, numbers and
# option sets never crash the interpreter and never raise anything but ValueError, TypeError,
# OSError or RuntimeError; what is accepted is what was given. Derandomized, so that every run
# tries the same cases; the whole file runs in well under two minutes.
import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import nimbus

ALLOWED = (ValueError, TypeError, OSError, RuntimeError)
SETTINGS = dict(derandomize=True, deadline=None, database=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

# Numbers as a hostile caller passes them: every float (NaN, infinities, subnormals, 1e308), ints
# far beyond 64 bits, bools, NumPy scalars, strings, None and containers.
numbers_of_all_kinds = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True), st.integers(min_value=-(10 ** 30), max_value=10 ** 30),
    st.booleans(), st.none(), st.text(max_size=8), st.just(np.float32(1.5)), st.just(np.int64(7)),
    st.lists(st.floats(allow_nan=True), max_size=4), st.just(object()))

def mostly(likely, other):
    """`likely` seven times in eight, else `other` (one_of does not weigh its branches)."""
    return st.sampled_from([True] * 7 + [False]).flatmap(lambda first: likely if first else other)


def usually(valid):
    """Mostly `valid` (values of the right type, in any range), now and then anything at all."""
    return mostly(valid, numbers_of_all_kinds)


dtypes = st.one_of(hnp.floating_dtypes(), hnp.integer_dtypes(), hnp.unsigned_integer_dtypes(), hnp.boolean_dtypes(),
                   hnp.complex_number_dtypes(), st.just(np.dtype(object)), st.just(np.dtype("U3")))


def arrays(max_dims=4):
    """Arrays of any of those dtypes and 0..max_dims dimensions of 0..6, some made strided by a step."""
    def make(dtype, shape):
        if dtype.kind == "O":
            elements = st.one_of(st.floats(allow_nan=True), st.text(max_size=2), st.none())
        elif dtype.kind in "fc":
            elements = hnp.from_dtype(dtype, allow_nan=True, allow_infinity=True)
        else:
            elements = None
        return hnp.arrays(dtype, shape, elements=elements)
    base = st.tuples(dtypes, hnp.array_shapes(min_dims=0, max_dims=max_dims, min_side=0, max_side=6)).flatmap(
        lambda t: make(*t))
    return st.one_of(base, base.map(lambda a: a[::2] if a.ndim else a), base.map(lambda a: a.T))


def real_arrays(dtypes, shape):
    """Arrays of real dtypes whose values are mostly small and non-negative, now and then NaN, inf or huge."""
    def make(dtype):
        if np.dtype(dtype).kind != "f":
            return hnp.arrays(dtype, shape)
        wild = st.floats(allow_nan=True, allow_infinity=True, width=16)
        return hnp.arrays(dtype, shape, elements=st.one_of(*[st.floats(0, 60000, width=16)] * 6, wild))
    return st.sampled_from(dtypes).flatmap(make)


densities = real_arrays([np.float32, np.float64, np.float16, np.int16, np.uint8, np.bool_],
                        hnp.array_shapes(min_dims=3, max_dims=3, min_side=1, max_side=5))


@settings(max_examples=300, **SETTINGS)
@given(array=mostly(densities, arrays()),
       voxel_size=usually(st.one_of(st.floats(1e-3, 1e3), st.floats(allow_nan=True, allow_infinity=True))),
       origin=usually(st.tuples(*[mostly(st.integers(-1000, 1000), st.integers(-(2 ** 40), 2 ** 40))] * 3)))
def test_from_array_takes_a_density_or_says_why(array, voxel_size, origin):
    try:
        v = nimbus.Volume.from_array(array, voxel_size, origin)
    except ALLOWED as e:
        event(f"refused: {type(e).__name__}: {str(e)[:25]}")
        return
    event("accepted")
    # Accepted: the very values, as float32, finite and >= 0.
    expected = np.asarray(array).astype(np.float32)
    if expected.size:
        np.testing.assert_array_equal(v.density, expected)
    assert np.all(np.isfinite(v.density)) and np.all(v.density >= 0)
    assert nimbus.VOXEL_SIZE_RANGE_M[0] <= v.voxel_size <= nimbus.VOXEL_SIZE_RANGE_M[1]


override_values = st.recursive(
    st.one_of(st.none(), st.booleans(), st.floats(allow_nan=True), st.integers(-(10 ** 20), 10 ** 20), st.text(max_size=6)),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.dictionaries(st.text(max_size=4), inner, max_size=3)),
    max_leaves=6)
override_keys = st.one_of(st.sampled_from(["coverage", "density", "seed", "shapes.0.size", "shapes", "wind", "period_m",
                                           "evolution", "cloud", "shapes.99.center", "a.b.c"]), st.text(max_size=12))


@settings(max_examples=250, **SETTINGS)
@given(preset=usually(st.sampled_from(["cumulus-humilis", "cumulus-field", "steam", "stratus", "nope"])),
       seed=usually(st.one_of(st.none(), st.integers(0, 2 ** 32 - 1), st.integers(-(2 ** 40), 2 ** 40))),
       voxel_size=usually(st.one_of(st.none(), st.floats(5.0, 200.0), st.floats(allow_nan=True, allow_infinity=True))),
       res=usually(st.one_of(st.none(), st.none(), st.integers(-10, 5000))),
       time=usually(st.one_of(st.floats(-1e4, 1e4), st.floats(allow_nan=True, allow_infinity=True))),
       overrides=usually(st.one_of(st.none(), st.none(), st.dictionaries(override_keys, override_values, max_size=2))))
def test_plan_takes_any_arguments_without_a_crash(preset, seed, voxel_size, res, time, overrides):
    try:
        p = nimbus.plan(preset, seed=seed, voxel_size=voxel_size, res=res, time=time, overrides=overrides)
    except ALLOWED as e:
        event(f"refused: {type(e).__name__}: {str(e)[:25]}")
        return
    event("accepted")
    assert p["voxel_size"] > 0 and all(n >= 0 for n in p["dims"])


@settings(max_examples=200, **SETTINGS)
@given(kind=usually(st.sampled_from(["value", "gradient", "wavelet", "worley"])),
       shape=usually(st.lists(mostly(st.integers(1, 9), st.integers(-3, 5000)), min_size=2, max_size=3)),
       frequency=usually(st.one_of(st.floats(0.01, 100), st.floats(allow_nan=True, allow_infinity=True))),
       octaves=usually(st.integers(-2, 12)),
       fractal=usually(st.sampled_from(["none", "fbm", "turbulence", "ridged"])),
       period=usually(st.one_of(st.just(0), st.integers(-5, 70))), time=usually(st.one_of(st.none(), st.floats(allow_nan=True))),
       spacing=usually(st.one_of(st.none(), st.none(), st.floats(allow_nan=True, allow_infinity=True))))
def test_noise_takes_any_arguments_without_a_crash(kind, shape, frequency, octaves, fractal, period, time, spacing):
    try:
        out = nimbus.noise(kind, shape, frequency=frequency, octaves=octaves, fractal=fractal, period=period,
                           time=time, spacing=spacing)
    except ALLOWED as e:
        event(f"refused: {type(e).__name__}: {str(e)[:25]}")
        return
    event("accepted")
    assert out.dtype == np.float32 and np.all(np.isfinite(out))


# File names as a hostile caller spells them: NUL, empty, very long, '%', flags, directories, devices.
# Generated names go into the test's folder; only these fixed ones are taken as they are.
AS_GIVEN = ["", "/dev/null", "/dev/zero", "/proc/self/mem", "/", "/etc/passwd"]
paths = st.one_of(st.text(max_size=20), st.sampled_from(AS_GIVEN + ["--help", "-o", "%d.exr", "a\0b.exr", ".", "x" * 5000 + ".exr"]),
                  st.binary(max_size=12), numbers_of_all_kinds)


def in_folder(folder, name):
    if isinstance(name, str) and name not in AS_GIVEN:
        return os.path.join(folder, name.lstrip("/"))
    if isinstance(name, bytes):
        return os.path.join(os.fsencode(folder), name.lstrip(b"/"))
    return name


images = real_arrays([np.float32, np.float64, np.float16, np.uint8],
                     st.tuples(st.integers(1, 6), st.integers(1, 6), st.just(4)))


@settings(max_examples=300, **SETTINGS)
@given(name=mostly(st.text(min_size=1, max_size=8).map(lambda s: s.replace("/", "_") + ".exr"), paths),
       image=mostly(images, arrays(max_dims=4)),
       exposure=usually(st.one_of(st.none(), st.floats(-100, 100))),
       metadata=usually(st.one_of(st.none(), st.dictionaries(st.text(max_size=6), st.text(max_size=6), max_size=3))))
def test_write_image_and_read_image_never_crash(tmp_path, name, image, exposure, metadata):
    target = in_folder(tmp_path, name)
    try:
        nimbus.write_image(target, image, exposure=exposure, metadata=metadata)
    except ALLOWED as e:
        event(f"write refused: {type(e).__name__}")
    else:
        event("written")  # written: it reads back as the image it was (half floats, clamped at 65504)
        back, _ = nimbus.read_image(target)
        expected = np.minimum(np.asarray(image, dtype=np.float32), 65504).astype(np.float16).astype(np.float32)
        np.testing.assert_array_equal(back, expected)
    try:
        nimbus.read_image(target)
    except ALLOWED:
        pass


@settings(max_examples=200, **SETTINGS)
@given(name=paths, grid=st.one_of(st.none(), st.text(max_size=6), numbers_of_all_kinds))
def test_read_takes_any_path_without_a_crash(tmp_path, name, grid):
    target = in_folder(tmp_path, name)
    try:
        nimbus.read(target, grid=grid)
    except ALLOWED:
        pass


_SMALL = nimbus.Volume.from_array(np.full((3, 3, 3), 0.4, np.float32), 40.0, origin=(-1, -1, 25))
render_option_names = st.sampled_from(["slices", "ms_photons", "sun_elevation", "time", "no_jitter"] * 3 + ["slices", "spp", "method", "no_jitter", "cloud_extinction", "ms_photons", "time",
                                       "sun_elevation", "sun_azimuth", "lamp", "preset", "colour", "repeat_to", "exposure",
                                       "ms_method", "cloud_phase", "shafts", "voxel_size"])


@settings(max_examples=40, **SETTINGS)
@given(options=st.dictionaries(render_option_names, usually(st.one_of(st.integers(-5, 5000), st.floats(allow_nan=True),
                                                                       st.sampled_from(["slices", "pathtrace", "none", "0,0,1"]))),
                               max_size=3),
       res=usually(st.just((12, 8))),
       eye=st.one_of(st.none(), st.tuples(*[st.floats(allow_nan=True, allow_infinity=True)] * 3), numbers_of_all_kinds))
def test_render_takes_any_options_without_a_crash(options, res, eye):
    options.setdefault("ms_photons", 2000)
    for heavy in ("ms_photons", "slices", "repeat_to"):  # their huge values' refusal is the program's test
        value = options.get(heavy)
        if isinstance(value, (int, float)) and not isinstance(value, bool) and 4096 < abs(value) < 1e9:
            options[heavy] = 4096
    try:
        image = nimbus.render(_SMALL, scene="none", res=res, eye=eye, **options)
    except ALLOWED as e:
        event(f"refused: {type(e).__name__}: {str(e)[:25]}")
        return
    event("accepted")
    assert image.ndim == 3 and image.shape[2] == 4 and np.all(np.isfinite(image))
