#!/usr/bin/env python3
"""docs/time-strip.png: what a frame's sky time means. One cumulus (cumulus-mediocris, its own seed) at
frames 0, 24, 48 and 72 of a 24 fps sequence: top row at the default --time-scale realtime (1/24 s
of sky a frame: 3 s in all), bottom row at --time-scale timelapse (10 s a frame: 12 minutes). Each
frame is rendered with `nimbus render --preset P --time T`, which is what `--frames` renders for
that frame; the camera frames the cloud each time, so it follows the wind's drift.

    scripts/render-time-strip.py [build-test/nimbus]
"""
import importlib.util
import os
import subprocess
import sys

PROGRAM = sys.argv[1] if len(sys.argv) > 1 else "build-test/nimbus"
HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("sheet", os.path.join(HERE, "render-preset-sheet.py"))
sheet_tools = importlib.util.module_from_spec(spec)
sys.argv = sys.argv[:1]  # the sheet module reads its own argv at import
spec.loader.exec_module(sheet_tools)

PRESET, RES, FPS = "cumulus-mediocris", "320x200", 24.0
FRAMES = (0, 24, 48, 72)
SCALES = (("realtime", 1.0 / FPS), ("timelapse", 10.0))


def main():
    images = []
    for name, seconds in SCALES:
        for f in FRAMES:
            t = f * seconds
            png = f"/tmp/nimbus-strip-{name}-{f}.png"
            subprocess.run([PROGRAM, "render", "--preset", PRESET, "--time", repr(t), "--res", RES,
                            "--sun-elevation", "40", "--sun-azimuth", "200", "--fov", "30", "-o", f"/tmp/nimbus-strip-{name}-{f}.exr",
                            "--preview", png], check=True, stdout=subprocess.DEVNULL)
            images.append(sheet_tools.read_png(png))
            print(name, f, f"t = {t:g} s", flush=True)
    sheet_tools.write_png("docs/time-strip.png", sheet_tools.sheet(images, columns=len(FRAMES)))


if __name__ == "__main__":
    main()
