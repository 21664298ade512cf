#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The test command: installs what is missing, builds, and runs every test with ctest; then the
# sanitizer stage (scripts/sanitize.sh: the C++ tests under AddressSanitizer and
# UndefinedBehaviorSanitizer) and the fuzzing stage (scripts/fuzz.sh: libFuzzer, 25 s per
# target). Extra arguments go to the first ctest only. DS_SKIP_SANITIZERS=1 skips both extra
# stages (for quick local runs; CI runs them).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
"$root/scripts/build.sh"
(cd "$build" && ctest --output-on-failure -j "${DS_TEST_JOBS:-1}" "$@")
if [ "${DS_SKIP_SANITIZERS:-0}" = 1 ]; then
  echo "DS_SKIP_SANITIZERS=1: sanitizer and fuzzing stages skipped."
  exit 0
fi
"$root/scripts/sanitize.sh"
"$root/scripts/fuzz.sh"
