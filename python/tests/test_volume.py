# Volume: the density as NumPy without a copy, files written and read back, arrays in and out.
import os

import numpy as np
import pytest

import nimbus


def test_density_is_a_view_of_the_volumes_own_voxels(tmp_path):
    v = nimbus.generate("cumulus-humilis", voxel_size=12.0)
    d = v.density
    assert d.dtype == np.float32 and d.ndim == 3 and d.flags["F_CONTIGUOUS"]
    assert not d.flags["OWNDATA"]  # a view, kept alive by the volume
    i, j, k = np.unravel_index(np.argmax(d), d.shape)
    d[i, j, k] = 3.5
    assert v.density[i, j, k] == 3.5  # the edit is the volume's
    v.write(tmp_path / "edited.vdb", half_float=False)
    assert nimbus.read(tmp_path / "edited.vdb").density[i, j, k] == 3.5


def test_write_and_read_round_trip(tmp_path):
    v = nimbus.generate("cumulus-humilis", voxel_size=12.0, time=5.0)
    v.write(tmp_path / "f.vdb", half_float=False)
    back = nimbus.read(tmp_path / "f.vdb")
    assert back.origin == v.origin and back.voxel_size == v.voxel_size and back.up_axis == "z"
    np.testing.assert_array_equal(back.density, v.density)
    for key in ("preset", "seed", "time", "units", "up_axis"):
        assert back.metadata[key] == v.metadata[key]
    v.write(tmp_path / "h.vdb")  # half floats
    np.testing.assert_array_equal(nimbus.read(tmp_path / "h.vdb").density, v.density.astype(np.float16).astype(np.float32))


def test_from_array_round_trip(tmp_path):
    rng = np.random.default_rng(3)
    a = rng.random((7, 5, 4)).astype(np.float32)
    a[a < 0.3] = 0.0
    a[0, 0, 0] = a[-1, -1, -1] = 0.9  # the box's corners are active: the file's box is the array's
    v = nimbus.Volume.from_array(a, 2.5, origin=(-3, 10, 40))
    assert v.origin == (-3, 10, 40) and v.voxel_size == 2.5 and v.up_axis == "z"
    np.testing.assert_array_equal(v.density, a)
    v.write(tmp_path / "a.vdb", half_float=False)
    back = nimbus.read(tmp_path / "a.vdb")
    assert back.origin == (-3, 10, 40) and back.voxel_size == 2.5
    np.testing.assert_array_equal(back.density, a)
    world = np.array(back.index_to_world) @ np.array([1, 2, 3, 1.0])
    np.testing.assert_allclose(world[:3], np.array([1, 2, 3]) * 2.5)


def test_from_array_takes_any_real_array_in_any_order():
    c = np.arange(24, dtype=np.float64).reshape(2, 3, 4)  # C order, doubles
    v = nimbus.Volume.from_array(c, 1.0)
    np.testing.assert_array_equal(v.density, c.astype(np.float32))
    assert v.density[1, 2, 3] == 23.0


def test_a_y_up_file_is_rewritten_as_it_was(tmp_path, run):
    run("generate", "--preset", "cumulus-humilis", "--voxel-size", "12", "--up", "y", "--float", "-o", tmp_path / "y.vdb")
    y = nimbus.read(tmp_path / "y.vdb")
    assert y.up_axis == "y"
    y.write(tmp_path / "y2.vdb", half_float=False)
    again = nimbus.read(tmp_path / "y2.vdb")
    assert again.up_axis == "y" and again.origin == y.origin
    np.testing.assert_array_equal(again.density, y.density)


def test_a_foreign_file_is_read_through_the_isolated_reader(tmp_path):
    import pyopenvdb as vdb
    grid = vdb.FloatGrid()
    grid.name = "smoke"
    dense = np.zeros((6, 5, 4), dtype=np.float32)
    dense[1:5, 1:4, 1:3] = 0.75
    dense[2, 2, 1] = -0.5  # negative: read as 0, with a warning
    grid.copyFromArray(dense, ijk=(10, 20, 30))
    grid.transform = vdb.createLinearTransform(voxelSize=0.5)
    vdb.write(str(tmp_path / "foreign.vdb"), grids=[grid])
    with pytest.warns(UserWarning, match="1 negative"):
        v = nimbus.read(tmp_path / "foreign.vdb")
    assert v.voxel_size == 0.5 and v.up_axis == "y"  # no up_axis metadata: y, as nimbus render assumes
    assert v.origin == (11, 21, 31)
    assert v.density.shape == (4, 3, 2)
    expected = dense[1:5, 1:4, 1:3].copy()
    expected[expected < 0] = 0.0
    np.testing.assert_array_equal(v.density, expected)
    # copyToArray's order is the volume's [x, y, z] order.
    assert v.density[1, 1, 0] == 0.0 and v.density[0, 0, 0] == 0.75


@pytest.mark.parametrize("array,voxel,origin,message", [
    (np.full((2, 2, 2), np.nan, np.float32), 1.0, (0, 0, 0), r"density\[0, 0, 0\] is NaN"),
    (np.full((2, 2, 2), -1.0, np.float32), 1.0, (0, 0, 0), "negative"),
    (np.full((2, 2, 2), np.inf, np.float32), 1.0, (0, 0, 0), "infinite"),
    (np.ones((2, 2), np.float32), 1.0, (0, 0, 0), "3 dimensions"),
    (np.ones((2, 2, 2), np.float32), 0.0, (0, 0, 0), "voxel_size"),
    (np.ones((2, 2, 2), np.float32), float("nan"), (0, 0, 0), "voxel_size"),
    # was OpenVDB's "ArithmeticError: Non-zero scale values required", naming no argument
    (np.ones((2, 2, 2), np.float32), 1e-300, (0, 0, 0), r"^voxel_size: must be within \[1e-06, 1e\+06\] metres, got 1e-300$"),
    (np.ones((2, 2, 2), np.float32), 1e300, (0, 0, 0), r"^voxel_size: .* got 1e\+300$"),
    # a finite float64 beyond float32: was called "infinite"
    (np.full((2, 2, 2), 1e300), 1.0, (0, 0, 0), r"^array\[0, 0, 0\] is 1e\+300, beyond float32's range"),
    (np.ones((2, 2, 2), np.float32), 1.0, (0, 0, 2 ** 31), "origin"),
    (np.ones((2, 2, 2), np.float32), 1.0, (0, 0), "origin"),
])
def test_from_array_refuses_what_is_not_a_density(array, voxel, origin, message):
    with pytest.raises(ValueError, match=message):
        nimbus.Volume.from_array(array, voxel, origin=origin)


def test_from_array_refuses_an_array_of_what_is_not_a_number_with_a_type_error():
    with pytest.raises(TypeError, match="^array: expected real numbers, got dtype <U1$"):
        nimbus.Volume.from_array(np.array([[["a"]]]), 1.0)
    with pytest.raises(TypeError, match="^voxel_size: expected a number, got str$"):
        nimbus.Volume.from_array(np.ones((2, 2, 2)), "1")


def test_write_refuses_a_density_made_nan_through_the_view(tmp_path):
    v = nimbus.Volume.from_array(np.ones((3, 3, 3), np.float32), 1.0)
    v.density[1, 2, 0] = np.nan
    with pytest.raises(ValueError, match=r"density\[1, 2, 0\] is NaN"):
        v.write(tmp_path / "nan.vdb")
    assert not (tmp_path / "nan.vdb").exists()


def test_write_makes_missing_folders_as_the_program_does_and_names_a_path_it_cannot_write(tmp_path):
    v = nimbus.Volume.from_array(np.ones((2, 2, 2), np.float32), 1.0)
    v.write(tmp_path / "new" / "folder" / "x.vdb")
    assert nimbus.read(tmp_path / "new" / "folder" / "x.vdb").density.shape == (2, 2, 2)
    (tmp_path / "blocker").write_text("a file, not a folder")
    with pytest.raises((OSError, RuntimeError), match="blocker"):
        v.write(tmp_path / "blocker" / "x.vdb")


def test_read_errors_name_the_file(tmp_path):
    with pytest.raises(FileNotFoundError):
        nimbus.read(tmp_path / "missing.vdb")
    with pytest.raises(IsADirectoryError):
        nimbus.read(tmp_path)
    (tmp_path / "junk.vdb").write_bytes(b"not a vdb file at all" * 10)
    with pytest.raises(RuntimeError, match="junk.vdb"):
        nimbus.read(tmp_path / "junk.vdb")
    nimbus.Volume.from_array(np.ones((2, 2, 2), np.float32), 1.0).write(tmp_path / "ok.vdb")
    with pytest.raises(ValueError, match="nope"):
        nimbus.read(tmp_path / "ok.vdb", grid="nope")
    data = (tmp_path / "ok.vdb").read_bytes()
    (tmp_path / "cut.vdb").write_bytes(data[: len(data) // 2])
    with pytest.raises(RuntimeError, match="cut.vdb"):
        nimbus.read(tmp_path / "cut.vdb")
