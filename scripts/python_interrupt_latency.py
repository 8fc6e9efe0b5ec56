#!/usr/bin/env python3
"""How long Ctrl+C takes to stop the Python module's long calls: SIGINT is sent 0.5 s into a long
generate, render or noise grid, and the time from the signal to the KeyboardInterrupt is
measured, 5 times each. With --sweep: a sky render (2^21 photons, 320x180) is stopped once at
every 0.1 s of its length instead, from 0.05 s to past its end, and the longest waits printed.
Run with the package on the path (installed, or PYTHONPATH=<build>/python)."""
import os
import sys
import signal
import statistics
import tempfile
import threading
import time

import nimbus


def latency(call, delay=0.5):
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(delay, send)
    timer.start()
    try:
        call()
    except KeyboardInterrupt:
        return time.monotonic() - sent[0]
    finally:
        timer.cancel()
    raise SystemExit("the call ended before the signal: make it longer")


def sweep(path):
    """The sky render stopped at every 0.1 s of its length; the signal may come after its end."""
    call = lambda: nimbus.render(path, res=(320, 180), ms_photons=1 << 21)
    start = time.monotonic()
    call()
    length = time.monotonic() - start
    waits = []
    delay = 0.05
    while delay < length:
        try:
            waits.append((latency(call, delay), delay))
        except SystemExit:  # it ended first
            pass
        delay += 0.1
    waits.sort(reverse=True)
    print(f"sky render of {length:.2f} s stopped {len(waits)} times; longest waits:",
          ", ".join(f"{1000 * w:.0f} ms at {d:.2f} s" for w, d in waits[:3]))


def main():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "c.vdb")
        nimbus.generate("cumulus-mediocris", voxel_size=12.0).write(path)
        if "--sweep" in sys.argv[1:]:
            sweep(path)
            return
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
