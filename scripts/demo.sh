#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: installs what is missing, builds, then runs the pvbatch demo on a real
# volume from a Debian package and writes the result and a picture to OUT (default: out/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
out="${1:-$root/out}"
"$root/scripts/build.sh"
mkdir -p "$out"
export PYTHONPATH="$build/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
"$root/scripts/with_xvfb.sh" pvbatch "$root/Examples/demo.py" \
  --plugin "$build/lib/paraview-5.11/plugins/DeformableSurface/DeformableSurface.so" \
  --output "$out"
