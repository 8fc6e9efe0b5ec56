# Long calls release the GIL, and Ctrl+C (SIGINT, KeyboardInterrupt) stops them part-way.
import os
import signal
import threading

import pytest

import nimbus

# Work that takes seconds on any machine: a fine cumulus, a path-traced frame.
LONG_GENERATE = dict(preset="cumulus-mediocris", voxel_size=3.0)


def interrupt_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_stops_a_long_generate_part_way():
    seen = []
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        nimbus.generate(**LONG_GENERATE, progress=seen.append)
    timer.cancel()
    assert seen, "the generation reported no progress before it was stopped"
    assert max(seen) < 0.9  # stopped part-way, not at the end
    # The stop was withdrawn: the next call runs to the end.
    assert nimbus.generate("cumulus-humilis", voxel_size=20.0).density.max() > 0


def test_an_exception_in_the_progress_callable_stops_the_work():
    class Stop(Exception):
        pass

    def progress(fraction):
        if fraction > 0.0:
            raise Stop()

    with pytest.raises(Stop):
        nimbus.generate(**LONG_GENERATE, progress=progress)
    assert nimbus.generate("cumulus-humilis", voxel_size=20.0).density.max() > 0


def test_ctrl_c_stops_a_long_render(tmp_path):
    path = tmp_path / "c.vdb"
    nimbus.generate("cumulus-humilis", voxel_size=12.0).write(path)
    timer = interrupt_after(0.5)
    # A row of 512 pixels at 2^20 paths each is about half an hour of work: a stop polled only
    # between rows would run past the test's time limit. The path tracer polls every 64 paths.
    with pytest.raises(KeyboardInterrupt):
        nimbus.render(path, scene="none", method="pathtrace", spp=1 << 20, res=(512, 2), sun=(0, 0, 1))
    timer.cancel()
    image = nimbus.render(path, scene="none", method="pathtrace", spp=1, res=(8, 6), sun=(0, 0, 1))
    assert image.shape == (6, 8, 4)


def test_a_long_generate_lets_other_python_threads_run():
    done = threading.Event()
    errors = []

    def work():
        try:
            nimbus.generate("cumulus-mediocris", voxel_size=6.0)
        except Exception as e:  # reported below
            errors.append(e)
        finally:
            done.set()

    thread = threading.Thread(target=work)
    thread.start()
    ticks = 0
    while not done.is_set():
        ticks += 1  # Python bytecode on this thread while the other is inside nimbus
        done.wait(0.001)
    thread.join()
    assert not errors
    assert ticks > 50  # the GIL was released: with it held, this loop could not have run meanwhile
