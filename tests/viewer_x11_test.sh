#!/usr/bin/env bash
# The viewer's real window (GLFW under Xvfb, llvmpipe) driven by real X input events (xdotool):
# Space pauses, a left drag orbits the camera, Ctrl+S saves the view state, Escape exits with 0.
# Then the same script run in a window and headless (EGL) gives the same images.
# The events queue in the X server and the viewer handles them in order, so nothing here waits
# on a clock: xdotool --sync waits for the window to appear, `wait` for the program to exit.
# Usage: viewer_x11_test.sh NIMBUS_BINARY   (runs itself again under xvfb-run)
set -euo pipefail
nimbus=$1
if [ -z "${NIMBUS_X11_INNER:-}" ]; then
  for tool in xvfb-run Xvfb xdotool; do
    command -v "$tool" >/dev/null || { echo "viewer_x11_test: $tool is missing (scripts/install-deps.sh installs it)"; exit 1; }
  done
  NIMBUS_X11_INNER=1 exec xvfb-run -a -s "-screen 0 1024x768x24 -nolisten tcp" "$0" "$nimbus"
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$nimbus" view --size 800x450 --state-out "$work/state.json" --screenshot-dir "$work" > "$work/log.txt" 2>&1 &
pid=$!
wid=$(xdotool search --sync --onlyvisible --name "nimbus view" | head -n 1)
xdotool windowfocus --sync "$wid"
xdotool key --clearmodifiers space
# A left drag over the 3D view, right of the panel.
xdotool mousemove --window "$wid" 600 220 mousedown 1
xdotool mousemove --window "$wid" 640 230
xdotool mousemove --window "$wid" 700 240 mouseup 1
xdotool key --clearmodifiers ctrl+s
xdotool key --clearmodifiers Escape
status=0
wait "$pid" || status=$?
cat "$work/log.txt"
[ "$status" -eq 0 ] || { echo "FAIL: nimbus view exited with $status"; exit 1; }
[ -f "$work/state.json" ] || { echo "FAIL: Ctrl+S saved no state"; exit 1; }
python3 - "$work/state.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s["time"]["paused"] is True, "Space did not pause: %r" % s["time"]
eye = s["camera"]["eye"]
home = [-600.0, -5200.0, 250.0]  # the default view state's eye, z up (render/sky/view_state.hpp)
moved = max(abs(a - b) for a, b in zip(eye, home))
assert moved > 1.0, "the drag did not orbit: eye %r" % eye
look = s["camera"]["look_at"]
assert max(abs(a - b) for a, b in zip(look, [400.0, 1500.0, 1500.0])) < 1e-6, "a tumble keeps the target: %r" % look
print("viewer_x11_test: paused, orbited by %.0f m, saved, exited 0" % moved)
PY

# Determinism: one script, in a window and headless.
cat > "$work/script.json" <<'JSON'
{"size": [160, 90], "frames": 3, "dt": 0.5, "screenshot_every": 1,
 "events": [{"frame": 1, "drag": [30, 5], "button": "left"}]}
JSON
"$nimbus" view --script "$work/script.json" --screenshot-dir "$work/window" > "$work/log2.txt" 2>&1 || { cat "$work/log2.txt"; echo "FAIL: windowed script"; exit 1; }
"$nimbus" view --script "$work/script.json" --headless --screenshot-dir "$work/headless" > "$work/log3.txt" 2>&1 || { cat "$work/log3.txt"; echo "FAIL: headless script"; exit 1; }
for n in 0001 0002 0003; do
  out=$("$nimbus" compare "$work/window/nimbus-$n.exr" "$work/headless/nimbus-$n.exr")
  case "$out" in
    *"rel_rmse 0 "*"max_rel 0 "*) ;;
    *) echo "FAIL: frame $n differs between the window and headless: $out"; exit 1 ;;
  esac
done
echo "viewer_x11_test: the script's frames are identical in a window and headless"
