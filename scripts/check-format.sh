#!/usr/bin/env bash
# Fails when a C++ file of the tree is not as clang-format 14 with the repository's .clang-format
# writes it, naming each file and line (another major version formats some constructs
# differently, so the check insists on 14). Fix with `clang-format -i FILE`.
set -euo pipefail
cd "$(dirname "$0")/.."

format=""
for candidate in clang-format-14 clang-format; do
  if command -v "$candidate" >/dev/null && "$candidate" --version | grep -q "version 14\."; then
    format="$candidate"
    break
  fi
done
if [ -z "$format" ]; then
  echo "check-format: clang-format 14 not found (scripts/install-deps.sh installs it)" >&2
  exit 1
fi

# The files git tracks or would track (new, not ignored); outside a git checkout every C++ file
# but the build trees.
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard '*.cpp' '*.h')
else
  mapfile -t files < <(find . -path ./build -prune -o \( -name '*.cpp' -o -name '*.h' \) -print)
fi
"$format" --dry-run --Werror "${files[@]}"
echo "check-format: ${#files[@]} files formatted as $format writes them"
