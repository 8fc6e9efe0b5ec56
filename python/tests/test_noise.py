# nimbus.noise samples the field `nimbus noise` writes.
import numpy as np
import pytest

import nimbus


@pytest.mark.parametrize("kind,fractal,octaves", [("gradient", "fbm", 4), ("worley", "none", 1), ("value", "ridged", 3)])
def test_noise_equals_the_programs_grid(run, tmp_path, kind, fractal, octaves):
    import pyopenvdb as vdb
    path = tmp_path / "n.vdb"
    run("noise", "--kind", kind, "--fractal", fractal, "--octaves", octaves, "--frequency", 4, "--res", 16, "--seed", 9,
        "-o", path)
    grid = vdb.read(str(path), "noise")
    theirs = np.zeros((16, 16, 16), np.float32)
    grid.copyToArray(theirs)  # [x, y, z], the module's order
    ours = nimbus.noise(kind, (16, 16, 16), frequency=4.0, fractal=fractal, octaves=octaves, seed=9)
    assert ours.shape == (16, 16, 16) and ours.dtype == np.float32
    np.testing.assert_array_equal(ours, theirs)


def test_a_2d_shape_is_the_z0_slice_of_its_3d_grid():
    plane = nimbus.noise("gradient", (12, 8), octaves=2, frequency=3.0)
    cube = nimbus.noise("gradient", (12, 8, 4), octaves=2, frequency=3.0, spacing=1.0 / 12)
    assert plane.shape == (12, 8)
    np.testing.assert_array_equal(plane, cube[:, :, 0])


def test_noise_is_animated_by_time_and_seeded():
    a = nimbus.noise("gradient", (8, 8, 8), time=0.5)
    b = nimbus.noise("gradient", (8, 8, 8), time=0.75)
    c = nimbus.noise("gradient", (8, 8, 8), time=0.5, seed=1)
    assert not np.array_equal(a, b) and not np.array_equal(a, c)
    np.testing.assert_array_equal(a, nimbus.noise("gradient", (8, 8, 8), time=0.5))


@pytest.mark.parametrize("kwargs,message", [
    (dict(kind="plasma"), "unknown noise kind"),
    (dict(fractal="none", octaves=3), "more than one octave"),
    (dict(octaves=0), "octaves"),
    (dict(frequency=-1.0), "frequency"),
    (dict(shape=(0, 4, 4)), "shape"),
    (dict(shape=(4,)), "2 or 3"),
    (dict(seed=-1), "seed"),
    (dict(frequency=float("inf")), "frequency"),
])
def test_noise_refuses_bad_arguments(kwargs, message):
    args = dict(kind="gradient", shape=(4, 4, 4))
    args.update(kwargs)
    kind, shape = args.pop("kind"), args.pop("shape")
    with pytest.raises(ValueError, match=message) as e:
        nimbus.noise(kind, shape, **args)
    assert "--" not in str(e.value)
