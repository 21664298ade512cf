#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Checks the rules of CONTRIBUTING.md ("Formatting and documents") that a script can check:
# - no commit hash in README.md, docs/METHOD.md, docs/SCALING.md, Filters/ or Testing/ (history
#   lives in git): a hex token of 7-40 characters there that git resolves to a commit fails;
# - README.md is at most 200 lines (a user's manual; results go to docs/RESULTS.md);
# - docs/PROPERTIES.md is what xml/*.xml gives (scripts/properties_page.py).
# Run by the ctest Docs.check; exits 1 on any failure, naming each.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
status=0

readme_lines=$(wc -l < README.md)
if [ "$readme_lines" -gt 200 ]; then
  echo "FAILED: README.md has $readme_lines lines (at most 200; results go to docs/RESULTS.md)"
  status=1
fi

if git rev-parse --git-dir > /dev/null 2>&1; then
  files=(README.md docs/METHOD.md docs/SCALING.md)
  while IFS= read -r f; do files+=("$f"); done < <(git ls-files Filters Testing)
  # path:token for every hex token of 7-40 characters in a text file (grep -I skips binaries).
  hits=$(grep -IoHwE '[0-9a-fA-F]{7,40}' "${files[@]}" 2>/dev/null || true)
  if [ -n "$hits" ]; then
    commits=$(cut -d: -f2 <<< "$hits" | sort -u |
      sed 's/$/^{commit}/' | git cat-file --batch-check='%(objectname) %(objecttype) %(rest)' 2>/dev/null |
      awk '$2 == "commit" {print $1}' || true)
    # Report by token: batch-check prints full names, so match each token as a prefix.
    while IFS=: read -r path token; do
      lower=$(tr 'A-F' 'a-f' <<< "$token")
      if grep -q "^$lower" <<< "$commits"; then
        echo "FAILED: $path names commit $token (history lives in git, not in this file)"
        status=1
      fi
    done <<< "$hits"
  fi
else
  echo "not a git checkout: the commit-hash check is skipped"
fi

if ! /usr/bin/python3 scripts/properties_page.py --check; then
  status=1
fi

[ "$status" = 0 ] && echo "check_docs: README $readme_lines lines, no commit hashes, docs/PROPERTIES.md current"
exit "$status"
