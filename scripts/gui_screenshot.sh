#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# gui_screenshot.sh OUT.png: the README's picture of the ParaView GUI running the one-click
# workflow (Examples/gui_one_click.py): the paraview client under a private Xvfb, a picture of
# the whole window (panels included) after it has solved. Needs the build and ImageMagick's
# `import` (apt-get install imagemagick); not part of the tests (gui_one_click.py tests the GUI).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-gui_one_click.png}")"
display=$(( 300 + RANDOM % 500 ))
Xvfb ":${display}" -screen 0 1600x1000x24 -nolisten tcp >/dev/null 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
sleep 2
cd "$root"
DISPLAY=":${display}" DS_SOURCE_DIR="$root" paraview --dr --script="$root/Examples/gui_one_click.py" \
  -geometry 1600x1000+0+0 >/dev/null 2>&1 &
client=$!
sleep "${DS_GUI_WAIT:-40}"  # loading, solving and drawing; the GUI gives no signal when done
DISPLAY=":${display}" import -window root "$out"
kill "$client" 2>/dev/null || true
echo "wrote $out"
