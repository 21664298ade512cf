#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# gui_pictures.sh [OUT_DIR]: the pictures of docs/GUI.md, one per step of the picked-points
# workflow in the ParaView GUI (Examples/gui_steps.py, DS_GUI_STEP=1..4), each a picture of the
# whole client window made by scripts/gui_screenshot.sh; written as OUT_DIR/gui_step<N>.png
# (default: Examples/). The last step solves the brain: it waits longest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/Examples}")"
mkdir -p "$out"
waits=(25 30 40 150)  # seconds for the client to load, compute and draw each step
for step in 1 2 3 4; do
  DS_GUI_STEP=$step DS_GUI_WAIT=${waits[$((step - 1))]} DS_GUI_SIZE=1600x1100 \
    "$root/scripts/gui_screenshot.sh" "$out/gui_step$step.png" "$root/Examples/gui_steps.py"
done
