#!/usr/bin/env bash
# The main job, from any working directory: builds atlasd's tools, simulates a robot driving
# through a generated building, and writes pictures a person can look at.
# Output goes to $ATLAS_DEMO_DIR (default: <repo>/out/demo).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${ATLAS_DEMO_DIR:-$ROOT/out/demo}
"$ROOT/scripts/install-deps.sh"

BUILD=$ROOT/build/release
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" -j "$(nproc)" --target atlas-sim atlas-render >/dev/null
BIN=$BUILD/bin

rm -rf "$OUT"
mkdir -p "$OUT"
echo "== simulating a building with loops and a robot driving through it"
"$BIN/atlas-sim" --rooms 24 --length-km 0.5 --seed 1 --out "$OUT/sim"
echo "== drawing"
"$BIN/atlas-render" --run "$OUT/sim" --png "$OUT/run.png" --svg "$OUT/run.svg"
echo
echo "Result: $OUT/run.png (and run.svg): the building, the true route, the odometry route"
echo "and the laser scans."
