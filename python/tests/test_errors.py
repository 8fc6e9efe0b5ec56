# Bad values raise ValueError, wrong types TypeError, failures at run time RuntimeError or OSError,
# with the program's one-line messages in Python's words (arguments, not flags); no argument
# crashes the interpreter.
import math
import re

import numpy as np
import pytest

import nimbus
from conftest import cli_error, python_words

GENERATE_NAMES = {"--set": "overrides", "--params": "params_file"}


@pytest.mark.parametrize("flags,kwargs", [
    (["--preset", "cumulus-nope"], dict(preset="cumulus-nope")),
    (["--preset", "cumulus-humilis", "--set", "nokey=1"], dict(preset="cumulus-humilis", overrides={"nokey": 1})),
    (["--preset", "cumulus-humilis", "--set", "coverage=-3"], dict(preset="cumulus-humilis", overrides={"coverage": -3})),
    (["--preset", "cumulus-humilis", "--voxel-size", "0.001"], dict(preset="cumulus-humilis", voxel_size=0.001)),
    (["--preset", "cumulus-humilis", "--voxel-size", "-2"], dict(preset="cumulus-humilis", voxel_size=-2.0)),
    (["--preset", "cumulus-humilis", "--res", "5", "--voxel-size", "3"], dict(preset="cumulus-humilis", res=5, voxel_size=3.0)),
    (["--preset", "cumulus-humilis", "--time", "1e300"], dict(preset="cumulus-humilis", time=1e300)),
])
def test_generate_errors_are_the_programs_usage_errors(run, tmp_path, flags, kwargs):
    code, _, stderr = run("generate", *flags, "-o", tmp_path / "x.vdb", check=False)
    assert code == 2, stderr
    preset = kwargs.pop("preset")
    with pytest.raises(ValueError) as e:
        nimbus.generate(preset, **kwargs)
    # The program may add a hint about its own flags ("; cut the field into bricks with --brick").
    said = str(e.value)
    # The memory available is measured at each call: another process (a build beside the tests)
    # may change it between the two.
    free = lambda text: re.sub(r"the [0-9.]+ GiB of memory available", "the N GiB of memory available", text)  # noqa: E731
    assert free(python_words(cli_error(stderr), GENERATE_NAMES)).startswith(free(said.split("; cut")[0]))
    assert "\n" not in said and "--" not in said


@pytest.mark.parametrize("kwargs,message", [
    (dict(seed=-1), "seed"), (dict(seed=2 ** 32), "seed"),
    (dict(res=0), "res"), (dict(voxel_size=math.nan), "voxel_size"), (dict(voxel_size=1e-300), "voxel_size"),
    (dict(time=math.inf), "time"), (dict(overrides={"coverage": math.nan}), "overrides: coverage"),
    (dict(overrides={"": 1}), "overrides"), (dict(params_file=""), "params_file"),
])
def test_generate_refuses_bad_python_values(kwargs, message):
    with pytest.raises(ValueError, match=f"^{message}") as e:
        nimbus.generate("cumulus-humilis", **kwargs)
    assert "--" not in str(e.value)


@pytest.mark.parametrize("kwargs,message", [
    (dict(seed=1.5), "seed: expected an integer, got float"), (dict(seed=True), "seed: expected an integer, got bool"),
    (dict(voxel_size="big"), "voxel_size: expected a number, got str"),
    (dict(overrides=[1, 2]), "overrides: expected a dict"), (dict(overrides={"a": object()}), "overrides: a: a value must be"),
    (dict(progress=3), "progress: expected a callable"), (dict(params_file=3), "params_file: expected a path"),
    (dict(coverage_map=object()), "coverage_map: expected a PNG path or a 2-D array"),
])
def test_generate_refuses_wrong_types_with_a_type_error_naming_the_argument(kwargs, message):
    with pytest.raises(TypeError) as e:
        nimbus.generate("cumulus-humilis", **kwargs)
    assert str(e.value).startswith(message), str(e.value)
    assert len(str(e.value)) < 160


def test_the_programs_check_only_refuses_the_box_plan_refuses(run, tmp_path):
    code, _, stderr = run("--check-only", "generate", "--preset", "cumulus-humilis", "--voxel-size", "0.001",
                          "-o", tmp_path / "x.vdb", check=False)
    assert code == 2
    with pytest.raises(ValueError) as e:
        nimbus.plan("cumulus-humilis", voxel_size=0.001)
    assert python_words(cli_error(stderr), GENERATE_NAMES).startswith(str(e.value).split("; cut")[0])
    assert "memory" in str(e.value)


def test_a_cloud_with_no_voxel_is_a_runtime_error(run, tmp_path):
    code, _, stderr = run("generate", "--preset", "cumulus-humilis", "--voxel-size", "5000", "-o", tmp_path / "x.vdb",
                          check=False)
    assert code == 1
    with pytest.raises(RuntimeError, match="no voxel of density"):
        nimbus.generate("cumulus-humilis", voxel_size=5000.0)


def test_a_params_file_that_is_not_there_names_itself(tmp_path):
    with pytest.raises((ValueError, OSError, RuntimeError), match="missing.json"):
        nimbus.generate("cumulus-humilis", params_file=str(tmp_path / "missing.json"))


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    path = tmp_path_factory.mktemp("errors") / "small.vdb"
    nimbus.Volume.from_array(np.ones((4, 4, 4), np.float32), 10.0, origin=(0, 0, 100)).write(path)
    return path


@pytest.mark.parametrize("flags,kwargs", [
    (["--slices", "1"], dict(slices=1)),
    (["--eye", "0,0"], dict(eye=(0, 0))),
    (["--eye", "1,2,nan"], dict(eye=(1, 2, math.nan))),
    (["--res", "0x5"], dict(res=(0, 5))),
    (["--fov", "0.5"], dict(fov=0.5)),
    (["--method", "magic"], dict(method="magic")),
    (["--scene", "moon"], dict(scene="moon")),
    (["--method", "pathtrace"], dict(method="pathtrace")),
    (["--cloud-phase", "hg:2"], dict(cloud_phase="hg:2")),
    (["--ms-photons", "0"], dict(ms_photons=0)),
])
def test_render_errors_are_the_programs_usage_errors(run, tmp_path, small, flags, kwargs):
    code, _, stderr = run("render", small, *flags, "-o", tmp_path / "x.exr", check=False)
    assert code == 2, stderr
    with pytest.raises(ValueError) as e:
        nimbus.render(small, **{**dict(up=None, fov=None, res=None), **kwargs})
    assert str(e.value) == python_words(cli_error(stderr)) and "--" not in str(e.value)


@pytest.mark.parametrize("kwargs,message", [
    (dict(colour=1), "not an option of render"),
    (dict(output="x.exr"), "returns one image"),
    (dict(frames="1-3"), "returns one image"),
    (dict(slices=[1, 2], lamp=None), "slices"),
    (dict(res=(5,)), "res"),
    (dict(eye="x"), "eye"),
])
def test_render_refuses_bad_python_arguments(small, kwargs, message):
    with pytest.raises(ValueError, match=message):
        nimbus.render(small, **kwargs)


def test_render_with_nothing_to_render_is_refused():
    with pytest.raises(ValueError, match="nothing to render"):
        nimbus.render([])
    with pytest.raises(TypeError, match=r"^volumes_or_paths\[0\]: int is neither a Volume nor a path"):
        nimbus.render([3])
    with pytest.raises(TypeError, match="^volumes_or_paths: expected a Volume, a VDB path or a list of them, got NoneType"):
        nimbus.render(None)


def test_render_of_a_missing_file_is_a_runtime_error_naming_it(run, tmp_path):
    code, _, stderr = run("render", tmp_path / "gone.vdb", "-o", tmp_path / "x.exr", check=False)
    with pytest.raises((RuntimeError, OSError)) as e:
        nimbus.render(tmp_path / "gone.vdb")
    assert "gone.vdb" in str(e.value) and code == 1


def test_write_image_refuses_what_is_not_an_image(tmp_path):
    with pytest.raises(ValueError, match=r"^image: .*got shape \(9, 16, 1\)$") as e:  # was a TypeError of 3.4 kB
        nimbus.write_image(tmp_path / "x.exr", [[[0.5]] * 16] * 9)
    assert len(str(e.value)) < 200
    with pytest.raises(TypeError, match="^image: expected a"):
        nimbus.write_image(tmp_path / "x.exr", [[["a"] * 4] * 2] * 2)
    with pytest.raises(ValueError, match="height, width, 4"):
        nimbus.write_image(tmp_path / "a.exr", np.zeros((4, 4, 3)))
    with pytest.raises(ValueError, match="not finite|NaN"):
        nimbus.write_image(tmp_path / "a.exr", np.full((2, 2, 4), np.nan))
    with pytest.raises(ValueError, match=".exr"):
        nimbus.write_image(tmp_path / "a.png", np.zeros((2, 2, 4)))
    assert not any(tmp_path.iterdir())
