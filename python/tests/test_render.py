# nimbus.render gives the pixels `nimbus render` writes for the same flags.
import numpy as np
import pytest

import nimbus


@pytest.fixture(scope="module")
def humilis(tmp_path_factory):
    path = tmp_path_factory.mktemp("render") / "humilis.vdb"
    v = nimbus.generate("cumulus-humilis", voxel_size=12.0)
    v.write(path, half_float=False)
    return v, path


def program_image(run, tmp_path, *flags):
    out = tmp_path / "cli.exr"
    run("render", *flags, "-o", out)
    return nimbus.read_image(out)[0]


def assert_same_pixels(ours, exr):
    """The program's EXR holds half floats: ours, rounded to half, must be those very values."""
    assert ours.dtype == np.float32 and ours.shape == exr.shape
    np.testing.assert_array_equal(ours.astype(np.float16).astype(np.float32), exr)
    assert np.isfinite(ours).all() and ours[..., 3].max() > 0.1  # the cloud covers pixels


def test_render_over_the_sky_equals_the_program(run, tmp_path, humilis):
    v, path = humilis
    ours = nimbus.render([v], eye=(900, -1800, 300), look_at=(0, 0, 1000), res=(96, 54), ms_photons=1 << 18)
    theirs = program_image(run, tmp_path, path, "--scene", "sky", "--eye", "900,-1800,300", "--look-at", "0,0,1000",
                           "--res", "96x54", "--ms-photons", "262144")
    assert_same_pixels(ours, theirs)


def test_camera_defaults_are_the_programs(run, tmp_path, humilis):
    """No up, fov or res: the program's defaults, so the same call gives the same picture (it once
    defaulted to fov 45 and 640x360 where the program uses the scene's camera)."""
    v, path = humilis
    ours = nimbus.render(v, scene="none", sun=(0.3, -0.5, 0.8), slices=32, ms_photons=1 << 16)
    theirs = program_image(run, tmp_path, path, "--scene", "none", "--sun", "0.3,-0.5,0.8", "--slices", "32",
                           "--ms-photons", "65536")
    assert ours.shape == (512, 512, 4)
    assert_same_pixels(ours, theirs)


def test_a_request_file_renders_as_its_values_given_as_keywords(tmp_path, humilis):
    """request= reads nimbus render --request's JSON: the same pixels as its values given one by
    one, and a keyword given with it overrides the file's value."""
    v, _ = humilis
    request = tmp_path / "request.json"
    request.write_text('{"camera": {"eye": [900, -1800, 300], "look_at": [0, 0, 1000], "fov": 40},'
                       ' "optics": {"phase": "hg:0.3", "multiple": 0, "ms_method": "octaves"},'
                       ' "renderer": {"slices": 32, "repeat_to": 0}}')
    given = dict(scene="none", res=(48, 27), sun=(0.3, -0.5, 0.8))
    ours = nimbus.render(v, request=str(request), **given)
    assert ours[..., 3].max() > 0.1  # the cloud covers pixels
    spelled = dict(eye=(900, -1800, 300), look_at=(0, 0, 1000), fov=40, cloud_phase="hg:0.3", multiple=0,
                   ms_method="octaves", slices=32, repeat_to=0, **given)
    np.testing.assert_array_equal(ours, nimbus.render(v, **spelled))
    np.testing.assert_array_equal(nimbus.render(v, request=str(request), slices=64, **given),
                                  nimbus.render(v, **(spelled | {"slices": 64})))


def test_render_of_a_path_equals_the_render_of_its_volume(humilis):
    v, path = humilis
    options = dict(scene="none", res=(48, 27), sun=(0.3, -0.5, 0.8), ms_photons=1 << 17, slices=64)
    np.testing.assert_array_equal(nimbus.render(v, **options), nimbus.render(str(path), **options))


def test_volumes_render_from_memory_in_the_order_given(tmp_path, humilis):
    """A y-up Volume and a path, in either order, render as their two files do: the Volume is
    the cloud its file would be, and keeps its place among the paths."""
    v, path = humilis
    y_path = tmp_path / "y.vdb"
    nimbus.Volume.from_array(np.asarray(v.density)[::2, ::2, ::2], 24.0, origin=(20, 30, 2), up_axis="y").write(
        y_path, half_float=False)
    y = nimbus.read(y_path)
    assert y.up_axis == "y"
    options = dict(scene="none", res=(48, 27), sun=(0.3, -0.5, 0.8), ms_photons=1 << 16, slices=48)
    for items, files in (([y, path], [str(y_path), str(path)]), ([path, y], [str(path), str(y_path)])):
        np.testing.assert_array_equal(nimbus.render(items, **options), nimbus.render(files, **options))


def test_a_volume_with_negative_values_renders_them_as_0_with_a_warning(humilis):
    """No file between: write refuses a negative value, render takes the Volume as it is and reads
    the negative values as 0, as nimbus render reads a file's."""
    v, _ = humilis
    dense = np.array(v.density)
    negative = nimbus.Volume.from_array(dense, 12.0, origin=v.origin)
    clipped = nimbus.Volume.from_array(dense, 12.0, origin=v.origin)
    negative.density[dense == 0] = -1.0  # the empty voxels become negative
    options = dict(scene="none", res=(32, 18), sun=(0.3, -0.5, 0.8), ms_photons=1 << 16, slices=32)
    with pytest.warns(UserWarning, match=r"volumes_or_paths \(a Volume\): grid 'density' holds \d+ negative"):
        ours = nimbus.render(negative, **options)
    np.testing.assert_array_equal(ours, nimbus.render(clipped, **options))


def test_a_volume_made_nan_through_its_view_is_refused_by_name(humilis):
    v, _ = humilis
    bad = nimbus.Volume.from_array(np.array(v.density), 12.0)
    bad.density[3, 3, 3] = np.nan
    with pytest.raises(ValueError, match=r"^volumes_or_paths\[1\] \(a Volume\): density\[3, 3, 3\] is NaN"):
        nimbus.render([v, bad], scene="none", res=(16, 16))


def test_path_tracer_options_pass_as_flags(run, tmp_path, humilis):
    v, path = humilis
    ours = nimbus.render(path, scene="none", method="pathtrace", spp=2, res=(32, 18), sun=(0, 0, 1), seed=5,
                         cloud_phase="hg:0.6", no_jitter=False)
    theirs = program_image(run, tmp_path, path, "--scene", "none", "--method", "pathtrace", "--spp", "2", "--res", "32x18",
                           "--sun", "0,0,1", "--seed", "5", "--cloud-phase", "hg:0.6")
    assert_same_pixels(ours, theirs)


def test_render_generates_presets_as_the_program_does(run, tmp_path):
    ours = nimbus.render([], preset="smoke", voxel_size=0.5, res=(40, 30), scene="none", sun=(0, 0, 1))
    theirs = program_image(run, tmp_path, "--preset", "smoke", "--voxel-size", "0.5", "--res", "40x30", "--scene", "none",
                           "--sun", "0,0,1")
    assert_same_pixels(ours, theirs)


def test_write_image_writes_what_read_image_reads(tmp_path, humilis):
    v, _ = humilis
    image = nimbus.render(v, scene="none", res=(32, 18), sun=(0, 0, 1), ms_photons=1 << 16)
    nimbus.write_image(tmp_path / "a.exr", image, preview=tmp_path / "a.png", metadata={"note": "test"})
    back, meta = nimbus.read_image(tmp_path / "a.exr")
    np.testing.assert_array_equal(back, image.astype(np.float16).astype(np.float32))
    assert meta["note"] == "test"
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_sun_by_elevation_or_time_of_day_is_the_direction_it_stands_for(humilis):
    """One Z-up world: sun_elevation/sun_azimuth and time_of_day place the sun the direction
    (x east, y north, z up) places it, and a different sun changes the picture."""
    v, _ = humilis
    options = dict(scene="none", res=(48, 27), ms_photons=1 << 16, slices=48)
    el, az = np.radians(30.0), np.radians(120.0)
    vector = (np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el))  # east, north, up
    by_angles = nimbus.render(v, sun_elevation=30, sun_azimuth=120, **options)
    by_vector = nimbus.render(v, sun=vector, **options)
    np.testing.assert_allclose(by_angles, by_vector, rtol=1e-4, atol=1e-6)
    noon = nimbus.render(v, time_of_day=12, latitude=45, day_of_year=81, **options)  # equinox: 45 degrees up, due south
    south = nimbus.render(v, sun_elevation=45, sun_azimuth=180, **options)
    np.testing.assert_allclose(noon, south, rtol=1e-3, atol=1e-5)
    assert np.abs(noon - by_angles).max() > 100 * np.abs(noon - south).max()
