#!/bin/sh
# Zips blender/nimbus_clouds for Blender's Preferences > Add-ons > Install... (written atomically).
#   scripts/make-blender-addon-zip.sh [OUT.zip]     (default: ./nimbus_clouds.zip)
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-nimbus_clouds.zip}
case "$out" in *.zip) ;; *) echo "make-blender-addon-zip: '$out' must end in .zip" >&2; exit 2 ;; esac
dir=$(dirname "$out")
[ -d "$dir" ] || { echo "make-blender-addon-zip: no folder '$dir' for '$out'" >&2; exit 2; }
tmp=$(mktemp "$dir/.nimbus_clouds.XXXXXX")
trap 'rm -f "$tmp"' EXIT INT TERM
python3 - "$repo/blender" "$tmp" <<'EOF'
import os, sys, zipfile
src, dst = sys.argv[1], sys.argv[2]
files = []
for root, dirs, names in os.walk(os.path.join(src, "nimbus_clouds")):
    dirs[:] = sorted(d for d in dirs if d != "__pycache__")
    files += [os.path.join(root, n) for n in sorted(names) if n.endswith(".py")]
if not any(f.endswith(os.sep + "__init__.py") for f in files):
    sys.exit(f"make-blender-addon-zip: no nimbus_clouds/__init__.py under {src}")
with zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as z:
    for f in files:
        z.write(f, os.path.relpath(f, src))
print(f"{len(files)} files")
EOF
chmod 644 "$tmp"
mv -f "$tmp" "$out"
trap - EXIT INT TERM
echo "wrote $out"
