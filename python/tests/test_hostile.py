# The module against a hostile user (issue 53's reproductions): nothing crashes or hangs the
# interpreter, every error is Python's (the argument named, TypeError for a wrong type), and a stop
# belongs to the call it was asked of.
import os
import signal
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import nimbus


def run_python(code, timeout=120):
    """Runs `code` in a fresh interpreter with this module on its path: (exit code, stderr)."""
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=timeout, env=os.environ.copy())
    return done.returncode, done.stderr


@pytest.mark.parametrize("use", ["v.voxel_size", "v.density", "v.metadata", "v.origin", "v.write(path)",
                                 "nimbus.render(v)", "repr(v)"])
def test_a_volume_that_was_never_constructed_is_a_type_error_not_a_crash(tmp_path, use):
    code, stderr = run_python(f"""
        import nimbus
        v = nimbus.Volume.__new__(nimbus.Volume)
        path = {str(tmp_path / "x.vdb")!r}
        try:
            {use}
        except TypeError as e:
            assert "Volume" in str(e) and "generate" in str(e), e
            print("TypeError:", e)
        else:
            raise SystemExit("no error")
    """)
    assert code == 0, stderr  # a segfault was -11
    with pytest.raises(TypeError, match="no constructor of its own"):
        nimbus.Volume()


def test_the_interpreter_exits_cleanly_while_a_daemon_thread_is_inside_a_long_call():
    # Was: "terminate called without an active exception" and SIGABRT.
    code, stderr = run_python("""
        import threading, time
        import nimbus
        started = threading.Event()
        def work():
            started.set()
            nimbus.generate("cumulus-mediocris", voxel_size=3)
        threading.Thread(target=work, daemon=True).start()
        started.wait()
        time.sleep(0.5)
    """)
    assert code == 0, stderr
    assert "terminate" not in stderr and "Fatal" not in stderr, stderr


def test_exit_while_a_daemon_thread_waits_on_a_long_noise_grid():
    code, stderr = run_python("""
        import threading, time
        import nimbus
        threading.Thread(target=lambda: nimbus.noise("worley", (512,) * 3, octaves=8), daemon=True).start()
        time.sleep(0.3)
    """)
    assert code == 0 and "terminate" not in stderr, stderr


@pytest.mark.parametrize("read", [nimbus.read_image, nimbus.read])
def test_a_fifo_is_refused_before_it_is_opened(tmp_path, read):
    # Was: read_image blocked forever on the FIFO, and Ctrl+C could not stop it.
    fifo = tmp_path / "f.exr"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match="FIFO") as e:
        read(fifo)
    assert str(fifo) in str(e.value)


def test_ctrl_c_stops_a_long_noise_grid_part_way():
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    # 512^3 Worley samples at 8 octaves take seconds; the grid polls its stop every ~4096 samples.
    with pytest.raises(KeyboardInterrupt):
        nimbus.noise("worley", (512,) * 3, octaves=8)
    timer.cancel()
    assert nimbus.noise("gradient", (4, 4, 4)).shape == (4, 4, 4)  # the stop was this call's alone


def test_a_path_that_looks_like_a_flag_is_a_path(tmp_path):
    # Was: CLI11's "This should be caught in your main function".
    with pytest.raises(FileNotFoundError) as e:
        nimbus.render("--help")
    assert "--help" in str(e.value) and "caught" not in str(e.value)


def test_options_speak_python():
    v = nimbus.Volume.from_array(np.ones((2, 2, 2), np.float32), 10.0, origin=(0, 0, 100))
    # Was: "Could not convert: --slices = --ms-method" (options became command-line text).
    with pytest.raises(TypeError, match="^slices: takes a value .*not True or False$"):
        nimbus.render(v, slices=True)
    with pytest.raises(TypeError, match="^no_jitter: expected True or False, got str$"):
        nimbus.render(v, no_jitter="yes")
    with pytest.raises(ValueError) as e:
        nimbus.render(v, slices=-5)
    assert str(e.value).startswith("slices") and "slices: must be in [2, 4096], got -5" in str(e.value)
    assert "--" not in str(e.value)
    # A value that looks like a flag stays a value.
    with pytest.raises(ValueError) as e:
        nimbus.render(v, method="--help")
    assert str(e.value).startswith("method") and "caught" not in str(e.value)


def test_an_error_about_a_volume_names_the_argument_not_a_temporary_file():
    far = nimbus.Volume.from_array(np.ones((2, 2, 2), np.float32), 1e6, origin=(0, 0, 1000))
    with pytest.raises((ValueError, RuntimeError)) as e:
        nimbus.render(far, scene="none")
    said = str(e.value)
    assert "volumes_or_paths (a Volume)" in said and "nimbus-render-" not in said, said
    assert "000000000" not in said, said  # numbers print as %g, not 1e300 with 308 digits


def test_wrong_types_are_type_errors_with_short_messages(tmp_path):
    cases = [
        (lambda: nimbus.noise("gradient", (4, 4, 4), octaves=2.5), "octaves: expected an integer, got float"),
        (lambda: nimbus.noise("gradient", "abc"), "shape: expected a sequence, got str"),
        (lambda: nimbus.noise("gradient", ["a", 4]), "shape[0]: expected an integer, got str"),
        (lambda: nimbus.noise(3, (4, 4)), "kind: expected a string, got int"),
        (lambda: nimbus.read(3), "path: expected a path"),
        (lambda: nimbus.preset(None), "name: expected a string, got NoneType"),
        (lambda: nimbus.write_image(tmp_path / "a.exr", np.zeros((2, 2, 4)), metadata=[1]), "metadata: expected a dict"),
        (lambda: nimbus.render(tmp_path / "x.vdb", res="640x360"), "res: expected a sequence, got str"),
        (lambda: nimbus.render(tmp_path / "x.vdb", res=("640", 360)), "res[0]: expected an integer, got str"),
        (lambda: nimbus.render(tmp_path / "x.vdb", eye=object()), "eye: expected a number"),
    ]
    for call, message in cases:
        with pytest.raises(TypeError) as e:
            call()
        assert str(e.value).startswith(message), (message, str(e.value))
        assert len(str(e.value)) < 160


def test_numbers_in_messages_are_numbers():
    with pytest.raises(ValueError) as e:
        nimbus.generate("cumulus-humilis", voxel_size=1e300)
    assert "1e+300" in str(e.value) and "0000000" not in str(e.value)
    with pytest.raises(ValueError) as e:
        nimbus.noise("gradient", (4, 4, 4), seed=10 ** 400)
    assert len(str(e.value)) < 160
