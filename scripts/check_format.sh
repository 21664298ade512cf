#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The code's form, checked in CI (the ctest Format.check): every tracked C++ file as clang-format
# (the repository's .clang-format) writes it, and every source file (C++, Python, CMake, shell)
# carrying an SPDX licence line. Run `clang-format -i FILE` to fix the first.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
status=0
if ! command -v clang-format >/dev/null; then
  echo "clang-format is missing (scripts/install-deps.sh installs it)"
  exit 1
fi
while IFS= read -r f; do
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "not clang-format clean: $f"
    status=1
  fi
done < <(git ls-files '*.h' '*.cxx')
while IFS= read -r f; do
  if ! grep -q "SPDX-License-Identifier" "$f"; then
    echo "no SPDX-License-Identifier line: $f"
    status=1
  fi
done < <(git ls-files '*.h' '*.cxx' '*.py' '*.sh' '*.cmake' '*CMakeLists.txt' .ci/run)
exit $status
