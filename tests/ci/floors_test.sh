#!/usr/bin/env bash
# The floors of lib/: each folder may include its own floor's files and those of
# the floors below it, never one above (README's Layout). A folder added to lib/
# must be given a floor here. Fails listing every include that runs up a floor.
# Usage: floors_test.sh [SOURCE_DIR]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
# Lowest first; folders on one line share a floor and may include each other.
floors=(
  "base"
  "asset"
  "animation gen"
  "skinning"
  "scene"
  "measuring"
  "result"
  "frame"
  "render"
  "gate"
  "advise"
  "reports"
)
declare -A floor_of
for i in "${!floors[@]}"; do
  for folder in ${floors[$i]}; do floor_of[$folder]=$i; done
done
status=0
for dir in "$root"/lib/*/; do
  folder=$(basename "$dir")
  [[ -n ${floor_of[$folder]:-} ]] || { echo "floors: lib/$folder has no floor (give it one in $0)"; status=1; }
done
checked=0
while IFS= read -r -d '' file; do
  rel=${file#"$root"/lib/}
  folder=${rel%%/*}
  [[ -n ${floor_of[$folder]:-} ]] || continue
  while IFS=: read -r line target; do
    to=${target%%/*}
    [[ -n ${floor_of[$to]:-} ]] || continue  # not a lib/ folder (glad/, a system header)
    checked=$((checked + 1))
    if ((floor_of[$to] > floor_of[$folder])); then
      echo "floors: lib/$rel:$line includes $target, a floor up ($folder is floor ${floor_of[$folder]}, $to ${floor_of[$to]})"
      status=1
    fi
  done < <(grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"]*/' "$file" | sed 's/^\([0-9]*\):[^"]*"\([^"]*\)".*/\1:\2/' || true)
done < <(find "$root/lib" \( -name '*.h' -o -name '*.cpp' \) -print0 | sort -z)
((checked > 0)) || { echo "floors: no include read under $root/lib"; exit 1; }
((status == 0)) && echo "floors: $checked includes across lib/, none runs up a floor"
exit $status
