#!/usr/bin/env bash
# The C++ sources as .clang-format lays them out: fails naming each file that
# clang-format would change (reformat with: git ls-files '*.cpp' '*.h' | xargs
# clang-format -i). Needs no build.
# Usage: format_test.sh [SOURCE_DIR]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$root"
command -v clang-format >/dev/null || { echo "format_test: no clang-format (apt-get install clang-format)" >&2; exit 77; }
[[ -d .git || -f .git ]] || { echo "format_test: not a git checkout" >&2; exit 77; }
mapfile -t files < <(git ls-files '*.cpp' '*.h')
bad=()
for file in "${files[@]}"; do
  [[ -f $file ]] || continue
  clang-format --dry-run -Werror "$file" >/dev/null 2>&1 || bad+=("$file")
done
if ((${#bad[@]})); then
  printf 'format_test: not laid out as .clang-format says: %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "format_test: ${#files[@]} files as .clang-format lays them out"
