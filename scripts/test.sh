#!/usr/bin/env bash
# Every test of atlasd, from any working directory:
#   1. release build, unit tests;
#   2. AddressSanitizer + UndefinedBehaviorSanitizer build, unit tests;
#   3. libFuzzer build (clang), a short run of every fuzzer over its seed corpus;
#   4. hardware-in-loop tests (label "hil"), real processes over real UDP multicast inside a
#      private network namespace, so that no packet leaves the machine; they run beside 1-3
#      (started once the release tree is built) and are printed last.
# Prints one closing line "total: N passed, M failed" and exits non-zero on any failure.
#
# Usage: scripts/test.sh   (no arguments; -h, --help: this text)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" none "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/install-deps.sh"

JOBS=$(nproc)
passed=0
failed=0

configure_and_build() {  # dir, cmake args...
  local dir=$1
  shift
  echo "== build $(basename "$dir")" >&2
  cmake -S "$ROOT" -B "$dir" "$@" >"$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; return 1; }
  cmake --build "$dir" -j "$JOBS"
}

tally() {  # adds the counts of a ctest log to the totals
  local log=$1 line bad total
  line=$(grep -E 'tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -n 1 || true)
  if [ -z "$line" ]; then
    grep -q 'No tests were found' "$log" && return 0
    echo "ctest printed no summary" >&2
    failed=$((failed + 1))
    return 0
  fi
  bad=$(sed -E 's/.* ([0-9]+) tests? failed out of ([0-9]+).*/\1/' <<<"$line")
  total=$(sed -E 's/.* failed out of ([0-9]+).*/\1/' <<<"$line")
  passed=$((passed + total - bad))
  failed=$((failed + bad))
}

run_ctest() {  # dir, ctest args...
  local dir=$1 log
  shift
  log=$(mktemp)
  ctest --test-dir "$dir" --output-on-failure -j "$JOBS" --timeout 600 "$@" 2>&1 | tee "$log" || true
  tally "$log"
  rm -f "$log"
}

mkdir -p "$ROOT/build"

# 1. Release.
configure_and_build "$ROOT/build/release" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DATLAS_WERROR=ON \
  -DATLAS_TESTS_UNOPTIMISED=ON -DATLAS_UNITY_TESTS=ON

# 4, started now: the hardware-in-loop tests, in a private network namespace, beside steps 1-3.
# They mostly wait on devices played at real time, so they run at this shell's priority while
# everything after them runs at nice 10: the daemons under test keep real time, and the builds
# and CPU-bound tests take the rest of the machine.
hil_pid=""
hil_log=""
if ctest --test-dir "$ROOT/build/release" -N -L hil | grep -q 'Total Tests: [1-9]'; then
  hil_log=$(mktemp)
  echo "== hardware-in-loop tests: started, output at the end" >&2
  setsid unshare -n bash -c '
    set -e
    ip link set lo up
    ip link set lo multicast on
    ip route add 224.0.0.0/4 dev lo
    export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
    ctest --test-dir "$1" --output-on-failure -j 1 --timeout 900 -L hil
  ' hil "$ROOT/build/release" >"$hil_log" 2>&1 &
  hil_pid=$!
  # A failed build below ends this script: the tests beside it end with it.
  trap 'kill -0 "$hil_pid" 2>/dev/null && kill -TERM -- "-$hil_pid"' EXIT
fi
renice -n 10 -p $$ >/dev/null

run_ctest "$ROOT/build/release" -LE hil

# 2. Sanitizers.
configure_and_build "$ROOT/build/sanitize" -DCMAKE_BUILD_TYPE=Debug -DATLAS_WERROR=ON -DATLAS_SANITIZE=ON \
  -DATLAS_BENCHMARKS=OFF -DATLAS_UNITY_TESTS=ON
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  run_ctest "$ROOT/build/sanitize" -LE hil

# 3. Fuzzers (clang, libFuzzer + ASan + UBSan): only the fuzz targets are built; ctest label
#    "fuzz" runs each over its seed corpus for a fixed number of inputs. Long runs: README.
echo "== build fuzz" >&2
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$ROOT/build/fuzz" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DATLAS_FUZZ=ON -DATLAS_BENCHMARKS=OFF >"$ROOT/build/fuzz.configure.log" 2>&1 ||
  { cat "$ROOT/build/fuzz.configure.log"; exit 1; }
mapfile -t fuzzers < <(cmake --build "$ROOT/build/fuzz" --target help | sed -nE 's/^\.\.\. ([a-z0-9_]+_fuzzer)$/\1/p')
if [ ${#fuzzers[@]} -gt 0 ]; then
  cmake --build "$ROOT/build/fuzz" -j "$JOBS" --target "${fuzzers[@]}"
  run_ctest "$ROOT/build/fuzz" -L fuzz
fi

# 4. Hardware-in-loop tests: collected here; printed and counted at the end.
if [ -n "$hil_pid" ]; then
  wait "$hil_pid" || true
  echo "== hardware-in-loop tests (ran beside steps 1-3)" >&2
  cat "$hil_log"
  tally "$hil_log"
  rm -f "$hil_log"
fi

echo "total: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
