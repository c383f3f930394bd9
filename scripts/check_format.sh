#!/usr/bin/env bash
# Fails, naming the files, when a C++ source of the repository is not as clang-format
# (.clang-format) writes it. Run `clang-format -i FILE` to fix one.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.h' '*.cpp')
unformatted=()
for f in "${files[@]}"; do
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
done
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "not formatted by clang-format: ${unformatted[*]}" >&2
  exit 1
fi
echo "${#files[@]} files formatted"
