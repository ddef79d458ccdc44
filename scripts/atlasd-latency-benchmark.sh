#!/usr/bin/env bash
# Runs atlasd's whole-path latency benchmark (tests/latency/atlasd_latency_benchmark.cc: last
# byte of a laser telegram on a pty -> ATLAS_POSE received by an LCM subscriber) inside a private
# network namespace, so that its LCM multicast never leaves the machine: lo only, multicast on,
# a route for 224.0.0.0/4 on lo, LCM_DEFAULT_URL udpm with ttl=0. Takes minutes (ATLAS_LATENCY_SECONDS
# of timed scans per variant, default 60); not a ctest.
#
#   ATLAS_BUILD_DIR=build/release scripts/atlasd-latency-benchmark.sh \
#     --benchmark_filter='fifo:40/sub_fifo:40/pin:0' --benchmark_repetitions=3
#
# Arguments go to the benchmark binary (Google Benchmark flags). Needs root for the real-time
# variants (SCHED_FIFO); without root the namespace is made in a user namespace (unshare -r)
# and the real-time settings are refused (atlasd says so on stderr). -h, --help: this text (the
# benchmark's own flags: ATLAS_BUILD_DIR/bin/atlasd_latency_benchmark --help).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" any "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${ATLAS_BUILD_DIR:-$ROOT/build/release}
BIN=$BUILD/bin/atlasd_latency_benchmark
if [ ! -x "$BIN" ]; then
  echo "atlasd-latency-benchmark: $BIN not found: build it with" >&2
  echo "  cmake --build $BUILD --target atlasd_latency_benchmark   (or set ATLAS_BUILD_DIR)" >&2
  exit 1
fi
userns=()
[ "$(id -u)" = 0 ] || userns=(-r)
exec unshare "${userns[@]}" -n bash -c '
  set -e
  ip link set lo up
  ip link set lo multicast on
  ip route add 224.0.0.0/4 dev lo
  export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
  echo "load average at start: $(cat /proc/loadavg)" >&2
  exec "$0" "$@"
' "$BIN" "$@"
