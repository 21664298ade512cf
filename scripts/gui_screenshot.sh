#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# gui_screenshot.sh OUT.png [SCRIPT.py]: a picture of the ParaView GUI, panels included, after the
# client has run SCRIPT.py (default: Examples/gui_one_click.py, the README's one-click picture):
# the paraview client under a private Xvfb with both plugins on PV_PLUGIN_PATH, then a picture of
# the whole screen (scripts/grab_x11.py). The client gives no signal when it is done: the picture
# is taken after DS_GUI_WAIT seconds (default 40), of a DS_GUI_SIZE screen (default 1600x1000). Needs the build; not part of the tests (the
# gui_* ctests test the GUI). Environment given to the script: DS_SOURCE_DIR, DS_PLUGIN.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-gui_one_click.png}")"
script="$(realpath "${2:-$root/Examples/gui_one_click.py}")"
plugins="$root/build/lib/paraview-5.11/plugins"
size="${DS_GUI_SIZE:-1600x1000}"
# The server takes a free display itself and writes its number once it accepts clients (as in
# scripts/with_xvfb.sh).
dfile=$(mktemp)
Xvfb -displayfd 3 -screen 0 "${size}x24" -nolisten tcp 3>"$dfile" >/dev/null 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -f "$dfile"' EXIT
for _ in $(seq 1 100); do
  [ -s "$dfile" ] && break
  sleep 0.1
done
display=$(head -n 1 "$dfile")
[ -n "$display" ] || { echo "gui_screenshot.sh: could not start an Xvfb server" >&2; exit 1; }
cd "$root"
DISPLAY=":${display}" DS_SOURCE_DIR="$root" DS_PLUGIN="$plugins/DeformableSurface/DeformableSurface.so" \
  PV_PLUGIN_PATH="$plugins/DeformableSurface:$plugins/DeformableSurfaceGUI" \
  paraview --dr --script="$script" -geometry "${size}+0+0" >/dev/null 2>&1 &
client=$!
sleep "${DS_GUI_WAIT:-40}"
/usr/bin/python3 "$root/scripts/grab_x11.py" ":${display}" "$out"
kill "$client" 2>/dev/null || true
echo "wrote $out"
