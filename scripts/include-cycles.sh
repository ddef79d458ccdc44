#!/usr/bin/env bash
# Lists the pairs of source folders that include each other in both directions (folder A has a
# file with #include "B/..." and folder B one with #include "A/..."), with one such include of
# each direction. Folders are the ones of the files (core/atlas, drivers/can, sim, ...), not
# their parents; a folder's tests and mains count as the folder's. Test-support folders
# (core/testing) are the exception: only tests, benchmarks and fakes may include them, and
# those includes are not folder dependencies. Exits 1 when a pair is found that is not allowed,
# when production code includes a test-support folder, or when an allowed pair is no longer
# there (then the allowance is stale: drop it); 0 otherwise.
#
# Usage: scripts/include-cycles.sh [--allow A:B]...
#   --allow A:B   the pair A <-> B is known and being removed elsewhere: reported, not a failure
# Runs as the ctest test "include_cycles".
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" any "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

declare -A allowed=()
while [ $# -gt 0 ]; do
  case $1 in
    --allow)
      [[ ${2:-} == ?*:?* ]] || { echo "include-cycles.sh: --allow takes A:B" >&2; exit 2; }
      a=${2%%:*} b=${2#*:}
      if [[ $a < $b ]]; then allowed["$a $b"]=1; else allowed["$b $a"]=1; fi
      shift 2
      ;;
    *)
      echo "include-cycles.sh: unknown argument '$1' (see scripts/include-cycles.sh --help)" >&2
      exit 2
      ;;
  esac
done

cd "$ROOT"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  list_sources() {
    git ls-files -co --exclude-standard -- '*.h' '*.cc' | while read -r f; do
      if [ -f "$f" ]; then echo "$f"; fi
    done
  }
else
  list_sources() { find . -path ./build\* -prune -o \( -name '*.h' -o -name '*.cc' \) -print | sed 's|^\./||'; }
fi

# "from-folder to-folder file" for every include of a file of another folder of this tree, one
# file per folder pair. Test-support folders (named testing, e.g. core/testing) hold test
# doubles of the modules whose tests use them: an include of one from a test, benchmark, fuzzer
# or fake_* file is not a folder dependency; from any other file it is reported (a test double
# in production code) as "production: ...".
edges=$(list_sources | tr '\n' '\0' |
  xargs -0 grep -HE '^[[:space:]]*#[[:space:]]*include[[:space:]]+"[^"]+/[^"/]+"' /dev/null |
  awk '{
    file = $0; sub(/:.*/, "", file)
    to = $0; sub(/^[^"]*"/, "", to); sub(/\/[^\/]*".*/, "", to)
    from = file; sub(/\/[^\/]*$/, "", from)
    test = file ~ /(_test|_benchmark|_fuzzer)\.cc$/ || file ~ /(^|\/)fake_[^\/]*$/ ||
           from ~ /(^|\/)testing$/
    if (to ~ /(^|\/)testing$/ && from != to) {
      if (!test) print "production:", to, file
      next
    }
    if (from != to && !((from " " to) in done)) { done[from " " to] = 1; print from, to, file }
  }' |
  while read -r from to file; do
    if [ "$from" = production: ] || [ -d "$to" ]; then echo "$from $to $file"; fi
  done || true)

status=0
found=0
declare -A seen=()
while read -r from to file; do
  [ -n "$from" ] || continue
  if [ "$from" = production: ]; then
    echo "production: $file includes the test-support folder $to"
    status=1
    continue
  fi
  back=$(awk -v a="$to" -v b="$from" '$1 == a && $2 == b {print $3; exit}' <<<"$edges")
  [ -n "$back" ] || continue
  if [[ $from < $to ]]; then key="$from $to"; else key="$to $from"; fi
  [ -z "${seen[$key]:-}" ] || continue
  seen[$key]=1
  found=$((found + 1))
  if [ -n "${allowed[$key]:-}" ]; then
    echo "allowed: $from <-> $to ($file; $back)"
  else
    echo "cycle: $from <-> $to ($file; $back)"
    status=1
  fi
done <<<"$edges"

for key in "${!allowed[@]}"; do
  if [ -z "${seen[$key]:-}" ]; then
    echo "stale allowance: ${key/ /:} no longer include each other both ways; drop the --allow"
    status=1
  fi
done
echo "include-cycles: $found folder pair(s) including each other both ways"
exit $status
