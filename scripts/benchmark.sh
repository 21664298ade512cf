#!/usr/bin/env bash
# Runs the benchmark programs (Testing/Benchmarks) and prints their tables.
# Usage: scripts/benchmark.sh [ScaleSpace|Solver|Hierarchy|HugeStart ...]   (default: all)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
"$root/scripts/build.sh" >/dev/null
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB"
echo "commit:  $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  names=(ScaleSpace Solver Hierarchy HugeStart)
fi
for n in "${names[@]}"; do
  exe="$build/bin/Bench$n"
  if [ -x "$exe" ]; then
    echo
    echo "== Bench$n"
    "$exe"
  else
    echo "Bench$n: not built" >&2
  fi
done
