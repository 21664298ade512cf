#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The fuzzing stage: builds the libFuzzer targets of Testing/Fuzz (clang, with AddressSanitizer
# and UndefinedBehaviorSanitizer, in the sanitizer build tree build-asan of scripts/sanitize.sh)
# and runs each for a bounded time, starting from its committed corpus
# Testing/Fuzz/corpus/<target>/ (regression inputs of past findings included, so they are
# replayed every time). New inputs go to a scratch copy, not into the repository. A finding (a
# crash, a sanitizer report, a broken promise of the filter, a leak, an input slower than
# FUZZ_TIMEOUT seconds) fails the script; libFuzzer saves the input as
# build-asan/fuzz/crash-* (or leak-*, timeout-*): add it to the corpus once fixed, and run
#   FUZZ_VERBOSE=1 build-asan/bin/Fuzz<target> <input>
# to see the points it decodes to (the two filter targets print them).
#
# Usage: scripts/fuzz.sh [target ...]
#   (default: RedGreen DelaunaySeed DeformableSurfaceInput NIfTIReader)
# FUZZ_SECONDS (default 25) is the time per target, FUZZ_SECONDS_NIFTI (default 60) that of
# NIfTIReader (the file reader gets a minute: its inputs are whole files, a header of many
# fields and gzip streams); FUZZ_SEED (default 1) fixes libFuzzer's
# random seed (runs still differ somewhat: its schedule depends on timing, so a finding can
# show in one run and not the next); FUZZ_SEED=0 takes a random seed for exploring locally. BUILD_ASAN_DIR as for scripts/sanitize.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_ASAN_DIR:-$root/build-asan}"
seconds="${FUZZ_SECONDS:-25}"
timeout="${FUZZ_TIMEOUT:-10}"
seed="${FUZZ_SEED:-1}"
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(RedGreen DelaunaySeed DeformableSurfaceInput NIfTIReader)
fi

"$root/scripts/sanitize.sh" --configure-only
cmake --build "$build" -j "$(nproc)" --target DSFuzzers
# FuzzDICOMReader is built only when the build found GDCM (libgdcm-dev): a default target then.
if [ $# -eq 0 ] && [ -x "$build/bin/FuzzDICOMReader" ]; then
  targets+=(DICOMReader)
fi

export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
work="$build/fuzz"
mkdir -p "$work"
cd "$work"
status=0
for t in "${targets[@]}"; do
  seconds_t="$seconds"
  if [ "$t" = NIfTIReader ]; then
    seconds_t="${FUZZ_SECONDS_NIFTI:-60}"
  fi
  scratch="$work/corpus-$t"
  rm -rf "$scratch"
  mkdir -p "$scratch"
  echo "== Fuzz$t: ${seconds_t} s from Testing/Fuzz/corpus/$t"
  # -rss_limit_mb: one execution of these small inputs needs far less; more is a finding.
  if ! "$build/bin/Fuzz$t" -seed="$seed" -max_total_time="$seconds_t" -timeout="$timeout" -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$work/" "$scratch" "$root/Testing/Fuzz/corpus/$t" \
    > "$work/Fuzz$t.log" 2>&1; then
    grep -v '^\s*#[0-9]\+\s' "$work/Fuzz$t.log" | tail -60
    echo "== Fuzz$t: FINDING (log: $work/Fuzz$t.log)"
    status=1
  else
    grep -E '^(Done|stat::number_of_executed_units|stat::average_exec_per_sec)' "$work/Fuzz$t.log" || true
    echo "== Fuzz$t: no finding"
  fi
done
exit $status
