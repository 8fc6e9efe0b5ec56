# nimbus.generate makes the voxels `nimbus generate` makes; plan says what it will make.
import numpy as np
import pytest

import nimbus


def cli_volume(run, tmp_path, *flags):
    path = tmp_path / "cli.vdb"
    run("generate", *flags, "-o", path)
    return nimbus.read(path)


def assert_same_voxels(a, b, atol=0.0):
    assert a.origin == b.origin
    assert a.voxel_size == b.voxel_size
    assert a.density.shape == b.density.shape
    np.testing.assert_allclose(a.density, b.density, rtol=0, atol=atol)


@pytest.mark.parametrize("preset,flags,kwargs", [
    ("cumulus-humilis", [], {}),
    ("cumulus-humilis", ["--seed", "7", "--voxel-size", "9", "--time", "30"], {"seed": 7, "voxel_size": 9.0, "time": 30.0}),
    ("steam", ["--res", "40", "--set", "density=0.5"], {"res": 40, "overrides": {"density": 0.5}}),
    ("cumulus-mediocris", ["--voxel-size", "20", "--set", "coverage=0.7", "--set", "shapes.0.size=[700,600,350]"],
     {"voxel_size": 20.0, "overrides": {"coverage": 0.7, "shapes.0.size": [700, 600, 350]}}),
    ("cumulus-humilis", ["--size", "2.5"], {"size": 2.5}),
    ("stratocumulus-field", ["--size", "0.5", "--voxel-size", "40"], {"size": 0.5, "voxel_size": 40.0}),
])
def test_generate_equals_the_program_voxel_for_voxel(run, tmp_path, preset, flags, kwargs):
    ours = nimbus.generate(preset, **kwargs)
    theirs = cli_volume(run, tmp_path, "--preset", preset, "--float", *flags)
    assert_same_voxels(ours, theirs)
    assert ours.density.max() > 0.0
    assert ours.metadata["preset"] == preset and ours.metadata["up_axis"] == "z"
    assert ours.metadata["seed"] == theirs.metadata["seed"] and ours.metadata["time"] == theirs.metadata["time"]


def test_generate_equals_the_programs_half_float_file_after_rounding(run, tmp_path):
    ours = nimbus.generate("cumulus-humilis")
    theirs = cli_volume(run, tmp_path, "--preset", "cumulus-humilis")  # half floats, the program's default
    rounded = ours.density.astype(np.float16).astype(np.float32)
    np.testing.assert_array_equal(rounded, theirs.density)
    assert np.abs(ours.density - theirs.density).max() > 0.0  # it is rounded: the comparison can tell


def test_a_hot_gas_carries_its_temperature_grid():
    steam = nimbus.generate("smoke", res=24)
    assert steam.extra_grids == ["temperature"]


def test_plan_names_the_box_generate_fills():
    p = nimbus.plan("cumulus-humilis", voxel_size=12.0)
    v = nimbus.generate("cumulus-humilis", voxel_size=12.0)
    assert p["voxel_size"] == v.voxel_size == 12.0
    nx, ny, nz = p["dims"]
    assert p["dense_bytes"] == nx * ny * nz * 4
    lo, hi = np.array(p["bounds_m"][0]), np.array(p["bounds_m"][1])
    # The active voxels lie inside the planned box.
    first = np.array(v.origin) * 12.0
    last = (np.array(v.origin) + np.array(v.density.shape) - 1) * 12.0
    assert np.all(first >= lo - 1e-9) and np.all(last <= hi + 1e-9)
    assert all(n >= m for n, m in zip(p["dims"], v.density.shape))


def test_plan_is_the_programs_plan_json(run):
    """One plan for every front end: Python's dict is `nimbus generate --plan-json`'s, key for key,
    and the default look in it is the one nimbus render uses (no optics flag given)."""
    import json
    for flags, kwargs in (([], {}), (["--size", "2", "--time", "60"], {"size": 2.0, "time": 60.0}),
                          (["--res", "50", "--seed", "4"], {"res": 50, "seed": 4})):
        _, out, _ = run("generate", "--preset", "cumulus-humilis", "--plan-json", *flags)
        theirs = json.loads(out)
        ours = nimbus.plan("cumulus-humilis", **kwargs)
        assert set(ours) == set(theirs)
        assert ours["dims"] == tuple(theirs["dims"]) and ours["voxel_size"] == theirs["voxel_size"]
        assert ours["bounds_m"] == tuple(tuple(c) for c in theirs["bounds_m"])
        assert ours["optics"] == theirs["optics"]
    assert nimbus.plan("cumulus-humilis")["optics"] == {
        "extinction_per_m": 0.04, "albedo": 0.99, "phase": {"g_forward": 0.7, "g_back": -0.25, "forward_weight": 0.8}}


def test_the_size_factor_grows_the_cloud_about_its_base():
    one, two = nimbus.plan("cumulus-humilis"), nimbus.plan("cumulus-humilis", size=2.0)
    assert two["voxel_size"] == 2 * one["voxel_size"] and two["dims"] == one["dims"]  # the preset's voxels, grown
    (lo1, hi1), (lo2, hi2) = one["bounds_m"], two["bounds_m"]
    assert lo2[2] == pytest.approx(lo1[2], abs=one["voxel_size"])  # the base stays at its altitude
    for a in (0, 1):
        assert hi2[a] - lo2[a] == pytest.approx(2 * (hi1[a] - lo1[a]), rel=0.05)
    with pytest.raises(ValueError, match=r"^size: must be within \[0.01, 100\], got 0$"):
        nimbus.generate("cumulus-humilis", size=0)
    with pytest.raises(TypeError, match="^size: expected a number"):
        nimbus.plan("cumulus-humilis", size="big")


def test_plan_refuses_what_generate_refuses():
    with pytest.raises(ValueError, match="memory"):
        nimbus.plan("cumulus-mediocris", voxel_size=0.01)
    with pytest.raises(ValueError, match="memory"):
        nimbus.generate("cumulus-mediocris", voxel_size=0.01)


def test_presets_and_preset_match_the_program(run):
    _, out, _ = run("presets")
    assert nimbus.presets() == [line.split()[0] for line in out.splitlines() if line.strip()]
    import json
    _, shown, _ = run("presets", "show", "cumulus-congestus")
    assert nimbus.preset("cumulus-congestus") == json.loads(shown)


def test_progress_is_reported_and_grows():
    seen = []
    nimbus.generate("cumulus-mediocris", voxel_size=8.0, progress=seen.append)
    assert seen == sorted(seen) and all(0.0 <= f <= 1.0 for f in seen)


def _grey_png(path, values):
    """An 8-bit grey PNG written with zlib alone (no imaging library here)."""
    import struct
    import zlib

    h, w = values.shape
    raw = b"".join(b"\x00" + bytes(int(v) for v in row) for row in values)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def test_generate_takes_a_coverage_map_as_a_png_or_an_array(run, tmp_path):
    # A 4 x 4 km field, its east half black: the program's --coverage-map, a path and an array agree,
    # and no voxel east of the black pixels' first centre holds cloud.
    over = {"field.size": [4000, 4000], "field.max_diameter": 1200}
    half = np.zeros((8, 16), dtype=np.uint8)
    half[:, :8] = 255
    png = tmp_path / "half.png"
    _grey_png(png, half)
    flags = ["--set", "field.size=[4000,4000]", "--set", "field.max_diameter=1200", "--voxel-size", "40"]
    theirs = cli_volume(run, tmp_path, "--preset", "cumulus-field", "--float", "--coverage-map", png, *flags)
    by_path = nimbus.generate("cumulus-field", voxel_size=40.0, overrides=over, coverage_map=str(png))
    by_array = nimbus.generate("cumulus-field", voxel_size=40.0, overrides=over, coverage_map=half / 255.0)
    assert_same_voxels(by_path, theirs)
    assert_same_voxels(by_array, theirs)
    d = by_path.density
    x = (by_path.origin[0] + np.arange(d.shape[0])) * by_path.voxel_size  # density is indexed x, y, z
    black = (x > -2000 + 8.5 * 250) & (x < 2000 - 0.5 * 250)
    assert d[~black].max() > 0.1
    assert d[black].max() == 0.0
    white = nimbus.generate("cumulus-field", voxel_size=40.0, overrides=over, coverage_map=np.ones((4, 4)))
    plain = nimbus.generate("cumulus-field", voxel_size=40.0, overrides=over)
    assert_same_voxels(white, plain)
    with pytest.raises(ValueError, match="coverage_map"):
        nimbus.generate("cumulus-field", voxel_size=40.0, overrides=over, coverage_map=np.full((4, 4), 2.0))
    with pytest.raises(RuntimeError, match="nowhere.png"):
        nimbus.generate("cumulus-field", voxel_size=40.0, overrides=over, coverage_map=str(tmp_path / "nowhere.png"))
