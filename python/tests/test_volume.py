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
    dense[2, 2, 1] = -0.5  # negative: kept as the file holds it
    grid.copyFromArray(dense, ijk=(10, 20, 30))
    grid.transform = vdb.createLinearTransform(voxelSize=0.5)
    vdb.write(str(tmp_path / "foreign.vdb"), grids=[grid])
    v = nimbus.read(tmp_path / "foreign.vdb")
    assert v.voxel_size == 0.5 and v.up_axis == "y"  # no up_axis metadata: y, as nimbus render assumes
    assert v.grid == "smoke"
    assert v.origin == (11, 21, 31)
    assert v.density.shape == (4, 3, 2)
    np.testing.assert_array_equal(v.density, dense[1:5, 1:4, 1:3])
    # copyToArray's order is the volume's [x, y, z] order.
    assert v.density[1, 1, 0] == -0.5 and v.density[0, 0, 0] == 0.75
    # A file nimbus writes holds a density: the negative value is refused, naming the voxel and the grid.
    with pytest.raises(ValueError, match=r"density\[1, 1, 0\] is negative.*grid is 'smoke'"):
        v.write(tmp_path / "back.vdb")


def test_read_keeps_a_noise_fields_negative_half(run, tmp_path):
    """A `nimbus noise` field is no density: its values, negative ones too, are read as stored
    (they were once set to 0, with a warning)."""
    run("noise", "--kind", "gradient", "--fractal", "fbm", "--octaves", 4, "--frequency", 4, "--res", 16, "--seed", 9,
        "-o", tmp_path / "n.vdb")
    v = nimbus.read(tmp_path / "n.vdb")
    assert v.grid == "noise" and v.origin == (0, 0, 0)
    field = nimbus.noise("gradient", (16, 16, 16), frequency=4.0, fractal="fbm", octaves=4, seed=9)
    assert (field < -0.05).any() and (field > 0.05).any()
    np.testing.assert_array_equal(v.density, field)
