#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs what is missing, then configures (once) and builds incrementally.
# BUILD_DIR (default: build) and extra CMake arguments in DS_CMAKE_ARGS may be set.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"

"$root/scripts/install-deps.sh"

if [ ! -f "$build/CMakeCache.txt" ]; then
  # The system python3 carries ParaView's vtkmodules; a pyenv shim on PATH would not.
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE=/usr/bin/python3 ${DS_CMAKE_ARGS:-}
fi
cmake --build "$build" -j "$(nproc)"
