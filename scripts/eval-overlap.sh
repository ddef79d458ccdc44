#!/usr/bin/env bash
# Buildings over buildings: simulated runs of several building kinds, one after another as one
# run (atlas-carmen --dump-carmen --append: each starts where the last ended, so its frames lie
# over the last buildings' frames in the atlas's projection), replayed with one configuration.
# A step whose dominant hypothesis lives in a frame made in an earlier building is localised in
# the wrong building: traversal matured a juvenile there (w and its probation let a map of
# another building explain the scans). The same happens to a robot whose odometry drifted over
# another mapped place, or on the floors of a building with one floor plan. Prints, per
# building after the first, the steps localised in an earlier building's frames and which
# frames, for each seed.
#
# Usage: scripts/eval-overlap.sh [OUT]      (default OUT: /tmp/atlas-eval-overlap)
# Environment: KINDS (default "office clutter corridor curved", in that order), SEEDS (default
# "1 2"), LENGTH_KM per building (default 0.5), ODOMETRY_NOISE (default | realistic), CONFIG
# (default <repo>/config/atlasd.toml), ATLAS_BIN (directory of atlas-sim, atlas-carmen,
# atlas-replay; default <repo>/build/release/bin, built if missing).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" out "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-/tmp/atlas-eval-overlap}
KINDS=${KINDS:-office clutter corridor curved}
SEEDS=${SEEDS:-1 2}
LENGTH_KM=${LENGTH_KM:-0.5}
ODOMETRY_NOISE=${ODOMETRY_NOISE:-default}
CONFIG=${CONFIG:-$ROOT/config/atlasd.toml}
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-sim atlas-carmen atlas-replay)
mkdir -p "$OUT"

echo "buildings over buildings: $KINDS, $LENGTH_KM km each, odometry noise $ODOMETRY_NOISE, $CONFIG"
for seed in $SEEDS; do
  dir=$OUT/seed-$seed
  rm -rf "$dir"
  mkdir -p "$dir"
  scans=()
  for kind in $KINDS; do
    "$BIN/atlas-sim" --quiet --kind "$kind" --seed "$seed" --length-km "$LENGTH_KM" \
      --odometry-noise "$ODOMETRY_NOISE" --sonar none --out "$dir/$kind" >/dev/null \
      2>"$dir/$kind.sim.txt" || { cat "$dir/$kind.sim.txt" >&2; exit 1; }
    "$BIN/atlas-carmen" --dump-carmen --append --out "$dir/run.log" "$dir/$kind/run.clf" \
      2>"$dir/$kind/dump.txt" || { cat "$dir/$kind/dump.txt" >&2; exit 1; }
    scans+=("$(sed -nE 's/.* and ([0-9]+) FLASER lines.*/\1/p' "$dir/$kind/dump.txt")")
  done
  "$BIN/atlas-replay" --quiet --config "$CONFIG" --out "$dir/replay" "$dir/run.log" >/dev/null
  python3 - "$dir/replay" "$seed" "$KINDS" "${scans[@]}" <<'PY'
import sys
out, seed, kinds = sys.argv[1], sys.argv[2], sys.argv[3].split()
counts = [int(n) for n in sys.argv[4:]]
ends, total = [], 0
for n in counts:
    total += n
    ends.append(total)
def building(step):  # steps count from 1
    return next(i for i, end in enumerate(ends) if step <= end)
made = {}
for line in open(out + "/frames.tsv"):
    if not line.startswith("#"):
        f = line.split()
        made[int(f[0])] = building(int(f[1]))
rows = [l.split() for l in open(out + "/trajectory.tsv") if not l.startswith("#")]
wrong = [0] * len(kinds)
frames = [set() for _ in kinds]
for step, row in enumerate(rows, start=1):
    b, f = building(step), int(row[1])
    if made[f] < b:
        wrong[b] += 1
        frames[b].add(f)
parts = ["%s %d of %d%s" % (kinds[b], wrong[b], counts[b],
                             " (frames %s)" % " ".join(map(str, sorted(frames[b])))
                             if frames[b] else "") for b in range(1, len(kinds))]
print("seed %s: %d frames; steps in an earlier building's frame: %s" % (
    seed, len(made), "; ".join(parts)))
PY
done
