#!/usr/bin/env python3
"""How long Ctrl+C takes to stop the Python module's long calls: SIGINT is sent 0.5 s into a long
generate, render or noise grid, and the time from the signal to the KeyboardInterrupt is
measured, 5 times each. Run with the package on the path (installed, or PYTHONPATH=<build>/python)."""
import os
import signal
import statistics
import tempfile
import threading
import time

import nimbus


def latency(call):
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.5, send)
    timer.start()
    try:
        call()
    except KeyboardInterrupt:
        return time.monotonic() - sent[0]
    finally:
        timer.cancel()
    raise SystemExit("the call ended before the signal: make it longer")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "c.vdb")
        nimbus.generate("cumulus-mediocris", voxel_size=12.0).write(path)
        calls = {
            "generate cumulus-mediocris at 3 m": lambda: nimbus.generate("cumulus-mediocris", voxel_size=3.0),
            "render, path tracer, 100000 spp": lambda: nimbus.render(path, scene="none", method="pathtrace", spp=100000,
                                                                   res=(64, 36), sun=(0, 1, 0)),
            "render, slices over the sky (light volume of 2^24 photons)": lambda: nimbus.render(
                path, res=(320, 180), ms_photons=1 << 24),
            "noise, Worley 512^3 at 8 octaves": lambda: nimbus.noise("worley", (512,) * 3, octaves=8),
        }
        print("| call | signal to KeyboardInterrupt, median | max |")
        print("|---|---:|---:|")
        for name, call in calls.items():
            times = [latency(call) for _ in range(5)]
            print(f"| {name} | {1000 * statistics.median(times):.0f} ms | {1000 * max(times):.0f} ms |")


if __name__ == "__main__":
    main()
