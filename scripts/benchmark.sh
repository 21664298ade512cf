#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs the benchmark programs (Testing/Benchmarks) and prints their tables.
# Usage: scripts/benchmark.sh [ScaleSpace|Solver|Hierarchy|HugeStart|Heads|Accuracy|Scale|Objects|SeveralObjects ...]
#   default: ScaleSpace Solver Hierarchy HugeStart (about 3 minutes). Heads (the README's
#   whole-head solves in VTK Python against vtkFlyingEdges3D; about a minute; BENCH_ARGS = the
#   runs of each), Accuracy (our filter, vtkFlyingEdges3D and ITK's geodesic active contour on
#   the accuracy phantoms; about 10 minutes) and Scale (128^3..1024^3 CT-like volumes, time and
#   peak memory, from the box, from a sphere near the object and one click;
#   about 5 minutes) and Objects (one click on the spine and horned
#   phantoms, Colin27's caudates and 50 white-matter clicks, beside a connected threshold, with
#   the goals; about 25 minutes, 30 s a white-matter click; BENCH_ARGS="spine horned"
#   runs the cases named, "--wm-clicks 10 wm" the first 10 clicks) and SeveralObjects
#   (several objects in one run with ObjectIds on the spine, assembly and engine phantoms and
#   Colin27's caudates and putamina, beside the same seeds as one object; about a minute;
#   BENCH_ARGS=ranges: the putamina again over a grid of typed ranges, 40 s) run when named.
#   Accuracy installs ITK (libinsighttoolkit5-dev, for the benchmark only) when it is missing;
#   ACCURACY_WITHOUT_ITK=1 does not install it (without ITK the table says that its column is
#   skipped and why).
# Arguments for one program: BENCH_ARGS, e.g. BENCH_ARGS="128 256" scripts/benchmark.sh Scale
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  names=(ScaleSpace Solver Hierarchy HugeStart)
fi

if [[ " ${names[*]} " == *" Accuracy "* && "${ACCURACY_WITHOUT_ITK:-0}" != 1 ]] &&
  ! dpkg-query -W -f='${Status}' libinsighttoolkit5-dev 2>/dev/null | grep -q "install ok installed"; then
  "$root/scripts/install-deps.sh" --with-itk
  # A configured build looked for ITK before it was there: look again.
  if [ -f "$build/CMakeCache.txt" ]; then
    cmake "$build" >/dev/null
  fi
fi

"$root/scripts/build.sh" >/dev/null
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB"
echo "commit:  $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
echo "load:    $(cut -d' ' -f1-3 /proc/loadavg) (1, 5, 15 min)"
for n in "${names[@]}"; do
  exe="$build/bin/Bench$n"
  script="$root/Testing/Benchmarks/Bench$n.py"
  if [ -f "$script" ]; then
    echo
    echo "== Bench$n"
    # shellcheck disable=SC2086
    PYTHONPATH="$build/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}" \
      /usr/bin/python3 "$script" ${BENCH_ARGS:-}
  elif [ -x "$exe" ]; then
    echo
    echo "== Bench$n"
    # shellcheck disable=SC2086
    "$exe" ${BENCH_ARGS:-}
  else
    echo "Bench$n: not built" >&2
  fi
done
