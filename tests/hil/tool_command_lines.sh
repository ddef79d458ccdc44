#!/usr/bin/env bash
# Every tool's command line follows tools/cli/command_line.h: --help (stdout, "Usage: NAME")
# and --version exit 0; an unknown option and an option without its value exit 2 with a message
# naming the option and "Try 'NAME --help'."; --opt=value is read as --opt value (the same exit
# status and messages). No network, no input files: every command line below stops before any
# work (a missing argument, a value out of range, or a configuration check).
# Usage: tool_command_lines.sh TOOL...   (the tools named below, by their file names)
source "$(dirname "$0")/hil_lib.sh"
[ $# -gt 0 ] || fail "no tools given"
declare -A path
for tool in "$@"; do path[$(basename "$tool")]=$tool; done

# common NAME [ARG...]: --help, --version and an unknown option (after ARG...).
common() {
  local name=$1
  shift
  local tool=${path[$name]:?"$name not given"}
  expect_exit 0 "^Usage: $name " "$tool" --help
  expect_exit 0 "^$name [0-9]" "$tool" --version
  expect_exit 2 "^$name: unknown option '--no-such-option'$" "$tool" "$@" --no-such-option
  grep -qx "Try '$name --help'." "$WORK/err" || fail "$name: no pointer to --help: $(cat "$WORK/err")"
  expect_exit 2 "^$name: unknown option '--no-such-option'$" "$tool" "$@" --no-such-option=1
}

# check NAME OPTION VALUE [ARG...]: common, OPTION without its value, OPTION=VALUE as OPTION VALUE.
check() {
  local name=$1 option=$2 value=$3
  shift 3
  local tool=${path[$name]} rc_eq=0 rc_sp=0
  common "$name" "$@"
  expect_exit 2 "^$name: $option needs a value$" "$tool" "$@" "$option"
  "$tool" "$@" "$option=$value" >"$WORK/eq.out" 2>"$WORK/eq.err" || rc_eq=$?
  "$tool" "$@" "$option" "$value" >"$WORK/sp.out" 2>"$WORK/sp.err" || rc_sp=$?
  [ "$rc_eq" = "$rc_sp" ] || fail "$name $option=$value exits $rc_eq, $option $value $rc_sp"
  cmp -s "$WORK/eq.err" "$WORK/sp.err" ||
    fail "$name $option=$value: $(cat "$WORK/eq.err") / $option $value: $(cat "$WORK/sp.err")"
  if grep -q "unknown option\|needs a value" "$WORK/eq.err"; then
    fail "$name $option=$value not read: $(cat "$WORK/eq.err")"
  fi
}

CONFIG=$(cd "$(dirname "$0")/../../config" && pwd)/atlasd.toml
check atlasd --check-config "$CONFIG"
grep -q "configuration is valid" "$WORK/eq.out" ||
  fail "atlasd --check-config=FILE: $(cat "$WORK/eq.out" "$WORK/eq.err")"
common atlas-check-config
expect_exit 0 "configuration is valid" "${path[atlas-check-config]}" -- "$CONFIG"
check atlas-fakedev --speed 2
grep -q "^atlas-fakedev: --log FILE is required" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-replay --max-scans 5
grep -q "^atlas-replay: no LOG given" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-replay --laser-max-range 0
grep -q "^atlas-replay: --laser-max-range must be a number in .*, got '0'" "$WORK/eq.err" ||
  fail "$(cat "$WORK/eq.err")"
check atlas-render --width 300
check atlas-refine --max-iterations 5
grep -q "^atlas-refine: no DIR given" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-refine --out x
check atlas-eval --tolerance 0.1
check atlas-carmen --log-max-range 50
grep -q "^atlas-carmen: no LOG given" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-carmen --left-scale-error 0.6
grep -q "^atlas-carmen: --left-scale-error must be a number in \[-0.5, 0.5\], got '0.6'" \
  "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
expect_exit 2 "^atlas-carmen: --append needs --dump-carmen and --out FILE" \
  "${path[atlas-carmen]}" --append --dump-carmen x.log
expect_exit 2 "^atlas-carmen: .*are different modes" "${path[atlas-carmen]}" --dump-carmen \
  --dump-odometry x.log
check atlas-sim --rooms 3
grep -q "^atlas-sim: --out DIR is required" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-sim --odometry-noise awful
grep -q "^atlas-sim: --odometry-noise must be one of default or realistic, got 'awful'" \
  "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-sonar-eval --lines 0 fig9
grep -q "^atlas-sonar-eval fig9: --lines must be an integer in \[1, 20\], got '0'" "$WORK/eq.err" ||
  fail "$(cat "$WORK/eq.err")"
expect_exit 2 "^atlas-sonar-eval: unknown MODE 'nope'" "${path[atlas-sonar-eval]}" nope
expect_exit 2 "^atlas-sonar-eval: no MODE given" "${path[atlas-sonar-eval]}"
check atlas-localmap-eval --runs 0 mc
check atlas-lcm-log-summary --poses "$WORK/p"
grep -q "^atlas-lcm-log-summary: no LOGFILE given" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-pose-latency --seconds 0
check atlas-carmen-to-lcm --max-scans -1
grep -q "^atlas-carmen-to-lcm: --max-scans must be an integer" "$WORK/eq.err" ||
  fail "$(cat "$WORK/eq.err")"
check atlas-export --resolution 0.5
grep -q "^atlas-export: no DIR given" "$WORK/eq.err" || fail "$(cat "$WORK/eq.err")"
check atlas-export --out x
check atlas-view --port 65536
grep -q "^atlas-view: --port must be an integer in \[0, 65535\], got '65536'" "$WORK/eq.err" ||
  fail "$(cat "$WORK/eq.err")"
check atlas-view --channel pose=ATLAS_GRAPH
grep -q "^atlas-view: --channel: two roles share the channel 'ATLAS_GRAPH'" "$WORK/eq.err" ||
  fail "$(cat "$WORK/eq.err")"
pass "$# tools: --help, --version, unknown options, missing values and --opt=value"
