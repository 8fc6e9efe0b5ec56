# The one table of render settings (render_settings.hpp in the library) as Python sees it: each
# setting the program's `nimbus render` takes is a typed keyword argument of render with the
# table's default, the program shows the same default and range, the docstring lists it, and a
# value just beyond its range is a ValueError naming the argument and the range. (The view state's
# side: tests/cpu/test_render_settings.cpp.)
import inspect
from typing import Optional

import numpy as np
import pytest

import nimbus

SETTINGS = nimbus._nimbus._render_settings()
FLAGS = {flag: (takes, default, text) for flag, takes, default, text in nimbus._nimbus._render_flags()}
OCTAVES_ONLY = {"ms-occlusion", "ms-contribution", "ms-eccentricity"}


def taken():
    return [s for s in SETTINGS if s["flag"] and "--" + s["flag"] in FLAGS]


def name_of(s):
    return s["flag"].replace("-", "_")


def outside(s):
    step = 1 if s["integer"] else max(1e-6, 1e-6 * (s["max"] - s["min"]))
    lo = s["min"] if s["min_open"] else s["min"] - step
    hi = s["max"] if s["max_open"] else s["max"] + step
    return [int(v) for v in (lo, hi)] if s["integer"] else [lo, hi]


@pytest.fixture(scope="module")
def volume():
    return nimbus.Volume.from_array(np.ones((2, 2, 2), np.float32), 10.0, origin=(0, 0, 100))


def test_every_setting_with_a_flag_is_an_argument_of_render(volume):
    params = inspect.signature(nimbus.render).parameters
    assert len(taken()) >= 15
    for s in SETTINGS:
        if not s["flag"]:
            continue
        if "--" + s["flag"] in FLAGS:
            assert name_of(s) in params, name_of(s)
            assert params[name_of(s)].kind in (inspect.Parameter.KEYWORD_ONLY,)
        else:  # the preview's exposure: render writes no file
            assert name_of(s) == "exposure"
            with pytest.raises(ValueError, match="^exposure: render returns one image"):
                nimbus.render(volume, exposure=1.0)


def test_defaults_and_ranges_are_the_tables_in_render_the_program_and_the_docstring():
    params = inspect.signature(nimbus.render).parameters
    for s in taken():
        name, flag = name_of(s), "--" + s["flag"]
        program_default, program_help = FLAGS[flag][1], FLAGS[flag][2]
        p = params[name]
        assert s["range"] in program_help, (flag, program_help)
        if s["default_text"]:  # a default in words: the argument is None, the program says it
            assert p.default is None, name
            assert program_default == "", (flag, program_default)
            assert "default: " + s["default_text"] in program_help, (flag, program_help)
        else:
            assert p.default == s["default"] and float(program_default) == s["default"], (name, p.default, program_default)
            assert p.annotation in ((int,) if s["integer"] else (float,)), (name, p.annotation)
        if name != "fov":  # fov is one of the camera's own arguments, described with them
            assert f"{name}: {s['help']}, {s['range']}" in nimbus.render.__doc__, name


def test_a_value_beyond_a_range_names_the_argument_and_the_range(volume):
    for s in taken():
        name = name_of(s)
        extra = {"ms_method": "octaves", "multiple": 2} if s["flag"] in OCTAVES_ONLY else {}
        for value in outside(s):
            with pytest.raises(ValueError) as e:
                nimbus.render(volume, **{name: value}, **extra)
            message = str(e.value)
            assert message.startswith(f"{name}: ") and f" in {s['range']}" in message, (name, value, message)


def test_every_default_spelled_out_gives_the_same_pixels_as_none(run, tmp_path):
    """The defaults are one: a render with every table setting (and the camera's fov 60) spelled
    out at its default gives the very pixels of the render with none, in Python and in the program,
    and the two agree. Octaves' scales are spelled out with the octaves they qualify."""
    cloud = nimbus.generate("cumulus-humilis", voxel_size=24.0)
    path = tmp_path / "c.vdb"
    cloud.write(path, half_float=False)
    base = dict(res=(48, 27), sun=(0.3, -0.5, 0.8))
    cli_base = ["--res", "48x27", "--sun", "0.3,-0.5,0.8"]
    for method, extra, cli_extra in ((None, {}, []), ("octaves", {"ms_method": "octaves", "multiple": 2},
                                                      ["--ms-method", "octaves", "--multiple", "2"])):
        spelled = {name_of(s): (int(s["default"]) if s["integer"] else s["default"]) for s in taken()
                   if not s["default_text"] and (s["flag"] in OCTAVES_ONLY) == (method == "octaves")}
        # The defaults stated in words, as they fall for this render: the sky scene's camera and
        # its repeat distance, no scene gas.
        spelled.update(fov=60.0, repeat_to=32000.0, cloud_extinction=0.04)
        assert len(spelled) >= (6 if method else 12), spelled
        plain = nimbus.render(cloud, **base, **extra)
        np.testing.assert_array_equal(nimbus.render(cloud, **base, **extra, **spelled), plain)
        flags = [f"--{k.replace('_', '-')}={v}" for k, v in spelled.items()]
        outs = []
        for i, more in enumerate(([], flags)):
            out = tmp_path / f"{method}-{i}.exr"
            run("render", path, *cli_base, *cli_extra, *more, "-o", out)
            outs.append(nimbus.read_image(out)[0])
        np.testing.assert_array_equal(outs[0], outs[1])
        np.testing.assert_array_equal(plain.astype(np.float16).astype(np.float32), outs[0])
        assert plain[..., 3].max() > 0.1
