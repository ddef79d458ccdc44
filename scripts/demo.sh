#!/usr/bin/env bash
# The main job, from any working directory: atlasd maps a simulated building on fake devices.
#  1. builds atlasd, every tool and the message types' jar for atlas-spy (release; not the
#     tests);
#  2. atlas-sim generates a building with loops and drives a robot through it (laser, sonar,
#     wheel odometry, as a CARMEN log);
#  3. inside a private network namespace (LCM multicast stays on its own loopback), atlas-fakedev
#     plays that log at $ATLAS_DEMO_SPEED times real time (default 4) as a SICK laser and a P2OS
#     sonar on pseudo-terminals and an AgileX base on a fake CAN bus; a real atlasd reads them
#     and maps, printing its health line every 5 s; lcm-logger records what it publishes;
#  4. atlasd stops (saving its atlas), the saved atlas is exported (atlasd --export-atlas) with
#     the poses it published, atlas-render draws the atlas atlasd built, and the simulated run,
#     and atlas-export writes the atlas as g2o, TUM, PLY and a map_server occupancy grid.
# Output goes to $ATLAS_DEMO_DIR (default: <repo>/out/demo). Takes about two minutes after the
# build. Needs root (or unprivileged user namespaces) for `unshare -n`.
#
# Usage: scripts/demo.sh   (no arguments; -h, --help: this text)
# Environment: ATLAS_DEMO_DIR, ATLAS_DEMO_SPEED, ATLAS_BUILD_DIR (default <repo>/build/release).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" none "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${ATLAS_DEMO_DIR:-$ROOT/out/demo}
SPEED=${ATLAS_DEMO_SPEED:-4}
BUILD=${ATLAS_BUILD_DIR:-$ROOT/build/release}
BIN=$BUILD/bin

if [ -z "${ATLAS_DEMO_IN_NETNS:-}" ]; then
  "$ROOT/scripts/install-deps.sh"
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  echo "== building atlasd and its tools (the first build takes a while)"
  cmake --build "$BUILD" -j "$(nproc)" --target atlas_tools >/dev/null
  rm -rf "$OUT"
  mkdir -p "$OUT"
  echo "== simulating a building with loops and a robot driving through it"
  "$BIN/atlas-sim" --rooms 16 --length-km 0.25 --seed 1 --sonar p3dx --out "$OUT/sim"
  # A private network namespace: LCM's multicast never leaves it.
  userns=()
  [ "$(id -u)" = 0 ] || userns=(-r)
  exec unshare "${userns[@]}" -n env ATLAS_DEMO_IN_NETNS=1 ATLAS_DEMO_DIR="$OUT" ATLAS_BUILD_DIR="$BUILD" \
    ATLAS_DEMO_SPEED="$SPEED" bash "${BASH_SOURCE[0]}"
fi

ip link set lo up
ip link set lo multicast on
ip route add 224.0.0.0/4 dev lo
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"

PIDS=()
cleanup() {
  local p
  for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null || true; done
}
trap cleanup EXIT

cat >"$OUT/atlasd.toml" <<TOML
# atlasd on atlas-fakedev playing the simulated run at $SPEED x real time (scripts/demo.sh)
[laser]
device = "$OUT/dev/laser"
unit = "cm"
max_range_m = 30.0
[odometry]
interface = "unix:$OUT/dev/can"
max_speed_mps = $(awk -v s="$SPEED" 'BEGIN { print 3 * s }')
slack_m = $(awk -v s="$SPEED" 'BEGIN { print 0.02 * s }')
[sonar]
enabled = true
device = "$OUT/dev/sonar"
[lcm]
url = "$LCM_DEFAULT_URL"
[state]
directory = "$OUT/state"
save_period_s = 1.0
TOML
# The simulated base is calibrated and its walls are straight: the simulator's noise models,
# not the shipped profile of a real B21.
cat "$ROOT/config/noise-simulator.toml" >>"$OUT/atlasd.toml"

echo "== atlasd on fake devices playing the run at ${SPEED}x real time"
lcm-logger --quiet --channel 'ATLAS_POSE|ATLAS_HEALTH' "$OUT/session.lcm" >"$OUT/logger.err" 2>&1 &
LOGGER=$!
PIDS+=("$LOGGER")
"$BIN/atlas-fakedev" --log "$OUT/sim/run.clf" --dir "$OUT/dev" --speed "$SPEED" \
  --wait-for-drivers --progress-every 0 >"$OUT/fakedev.out" 2>"$OUT/fakedev.err" &
FAKEDEV=$!
PIDS+=("$FAKEDEV")
for _ in $(seq 100); do [ -e "$OUT/dev/laser" ] && [ -e "$OUT/dev/can" ] && break; sleep 0.05; done
"$BIN/atlasd" --config "$OUT/atlasd.toml" --health-every 5 2> >(tee "$OUT/atlasd.err" >&2) &
ATLASD=$!
PIDS+=("$ATLASD")
wait "$FAKEDEV" || { echo "atlas-fakedev failed: $(tail -n 3 "$OUT/fakedev.err")" >&2; exit 1; }
sleep 1
kill -TERM "$ATLASD"
wait "$ATLASD" || { echo "atlasd exited with an error (see $OUT/atlasd.err)" >&2; exit 1; }
sleep 0.3
kill -INT "$LOGGER"  # lcm-logger ends its file at an event (atlas-lcm-log-summary refuses a cut one)
wait "$LOGGER" || true

echo "== drawing the atlas atlasd built"
"$BIN/atlasd" --config "$OUT/atlasd.toml" --export-atlas "$OUT/atlas"
# The published poses as a replay's trajectory.tsv (docs/formats.md).
"$BIN/atlas-lcm-log-summary" "$OUT/session.lcm" --trajectory "$OUT/atlas/trajectory.tsv" \
  >"$OUT/session.txt"
# The same atlas in the formats other tools read: g2o, TUM, PLY, map_server PGM + YAML.
"$BIN/atlas-export" "$OUT/atlas" --out "$OUT/atlas/export" >"$OUT/export.txt"
"$BIN/atlas-render" --atlas "$OUT/atlas" --whole --png "$OUT/atlas.png"
"$BIN/atlas-render" --run "$OUT/sim" --png "$OUT/run.png"
echo
echo "Result: $OUT/atlas.png: the atlas atlasd built (its frames placed from frame 0, their lines,"
echo "the laser points they keep, and the poses it published); $OUT/run.png: the simulated building and run; the saved atlas"
echo "is $OUT/state/atlas.sqlite, atlasd's log $OUT/atlasd.err; $OUT/atlas/export/ holds it as g2o,"
echo "TUM, PLY and a map_server occupancy grid (map.pgm, map.yaml)."
