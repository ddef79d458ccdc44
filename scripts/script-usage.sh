# Sourced by the scripts in this directory, right after `set -euo pipefail`:
#   source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
#   script_usage "${BASH_SOURCE[0]}" ARGS "$@"
# -h or --help prints the calling script's header comment (from line 2 to `set -euo`) and exits
# 0. ARGS says what else the script takes: "none" (any argument is a usage error), "out" (at
# most one argument, an output directory, never a dash-option) or "any" (passed on, unchecked).
# A usage error exits 2.
script_usage() {
  local script=$1 takes=$2
  shift 2
  local name
  name=$(basename "$script")
  if [[ ${1:-} == -h || ${1:-} == --help ]]; then
    sed -n '2,/^set -euo/p' "$script" | sed '$d' | sed 's/^# \{0,1\}//'
    exit 0
  fi
  if [[ $takes == none && $# -gt 0 ]]; then
    echo "$name: takes no arguments, got '$1' (see scripts/$name --help)" >&2
    exit 2
  fi
  if [[ $takes == out && (${1:-} == -* || $# -gt 1) ]]; then
    echo "$name: unknown option or extra argument: $* (usage: scripts/$name [OUT]; see --help)" >&2
    exit 2
  fi
}
