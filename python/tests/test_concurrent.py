# Calls in several threads at once, one of them stopped: the stop is that call's alone. Each of the
# others ends with exactly the result it has when it runs by itself. The others take seconds, so
# that they are still running when the stop comes (with one process-wide stop flag they raised).
import os
import signal
import threading

import numpy as np
import pytest

import nimbus

LONG_GENERATE = dict(preset="cumulus-mediocris", voxel_size=3.0)  # seconds of work on any machine


class Stop(Exception):
    pass


def small_volume():
    return nimbus.Volume.from_array(np.linspace(0.0, 0.5, 6 * 5 * 4, dtype=np.float32).reshape(6, 5, 4), 40.0,
                                    origin=(-3, -2, 25))


def render_small(volume):
    return nimbus.render(volume, scene="none", res=(96, 64), sun=(0.3, -0.2, 0.9), ms_photons=1 << 20,
                         eye=(0, -900, 1100), look_at=(0, 0, 1080))


def noise_grid():
    return nimbus.noise("worley", (320, 320, 320), octaves=6, seed=7)


def other_generate():
    return nimbus.generate("cumulus-mediocris", voxel_size=4.0)


def run_in_threads(jobs):
    """Runs each job (name -> callable) in a thread of its own, all at once; name -> (result, error)."""
    out = {}
    start = threading.Barrier(len(jobs))

    def run(name, job):
        start.wait()
        try:
            out[name] = (job(), None)
        except BaseException as e:  # reported to the test
            out[name] = (None, e)

    threads = [threading.Thread(target=run, args=item) for item in jobs.items()]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


def test_four_calls_at_once_one_stopped_by_its_progress(tmp_path):
    volume = small_volume()
    alone_render = render_small(volume)
    alone_noise = noise_grid()
    seen = []

    def stopped_generate():
        def progress(fraction):
            seen.append(fraction)
            if fraction > 0.25:  # a second or more in: the others are at work
                raise Stop()
        return nimbus.generate(**LONG_GENERATE, progress=progress)

    def write_and_read():
        path = tmp_path / "w.vdb"
        volume.write(path, half_float=False)
        return nimbus.read(path).density.copy()

    results = run_in_threads({"generate": stopped_generate, "render": lambda: render_small(volume),
                              "noise": noise_grid, "write": write_and_read})
    _, error = results["generate"]
    assert isinstance(error, Stop), error  # the progress's own exception, raised from generate
    assert seen and max(seen) < 0.9
    for name in ("render", "noise", "write"):
        assert results[name][1] is None, f"{name} failed: {results[name][1]!r}"
    np.testing.assert_array_equal(results["render"][0], alone_render)
    np.testing.assert_array_equal(results["noise"][0], alone_noise)
    np.testing.assert_array_equal(results["write"][0], volume.density)


def test_ctrl_c_stops_the_main_threads_call_alone():
    alone_noise = noise_grid()
    others = {}

    def other(name, job):
        try:
            others[name] = (job(), None)
        except BaseException as e:
            others[name] = (None, e)

    alone_generate = other_generate().density.copy()
    threads = [threading.Thread(target=other, args=("noise", noise_grid)),
               threading.Thread(target=other, args=("generate", other_generate))]
    for t in threads:
        t.start()
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        nimbus.generate(**LONG_GENERATE)
    timer.cancel()
    for t in threads:
        t.join()
    assert others["noise"][1] is None and others["generate"][1] is None, others
    np.testing.assert_array_equal(others["noise"][0], alone_noise)
    np.testing.assert_array_equal(others["generate"][0].density, alone_generate)
