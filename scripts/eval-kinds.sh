#!/usr/bin/env bash
# The simulator's building kinds (sim/building_kinds.h: curved, clutter, glass, corridor, hall,
# campus, people; office too) over many seeds. For each kind and seed: atlas-sim --kind K
# --seed S (LENGTH_KM of route, odometry at the ODOMETRY_NOISE level), atlas-replay with the
# shipped configuration (config/atlasd.toml, the same for every kind) and the run's truth as
# its reference (closures.tsv: false loop closures), then atlas-eval against relations made
# from the truth at the scans (scripts/relations-from-reference.py): pose pairs 1 m of travel
# apart, and returns (the nearest earlier pose within 1.5 m, at least 60 s and 20 m of travel
# earlier). The atlas's relations are composed along its Dijkstra paths (atlas-eval --atlas);
# dead reckoning of the same odometry on the same relations beside them.
# One line per kind (scripts/relations-summary.py): mean error over all relations (atlas,
# odometry; the seeds where the atlas is no worse), mean error on the returns (atlas,
# odometry), false closures (chi2 3 dof > 14.16), returns joined (same frame, neighbouring
# frames or a map-match edge) of all returns (a return whose frames the atlas never connected
# is scored by neither mean, but counted), step CPU time (median of medians, largest max).
# Pictures of the first seed per kind: OUT/K-world.png (world, truth, odometry, scans) and
# OUT/K-atlas.png (the atlas's whole run).
#
# Usage: scripts/eval-kinds.sh [OUT]      (default OUT: /tmp/atlas-eval-kinds)
# Environment: SEEDS (default 1..20), KINDS (default every kind, office first), LENGTH_KM
# (default 0.5), ODOMETRY_NOISE (default | realistic, default default), JOBS (default 2),
# ATLAS_BIN (directory of atlas-sim, atlas-replay, atlas-eval, atlas-render; default
# <repo>/build/release/bin, built if missing), CONFIG (default <repo>/config/atlasd.toml).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" out "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-/tmp/atlas-eval-kinds}
SEEDS=${SEEDS:-$(seq -s ' ' 1 20)}
KINDS=${KINDS:-office curved clutter glass corridor hall campus people}
LENGTH_KM=${LENGTH_KM:-0.5}
ODOMETRY_NOISE=${ODOMETRY_NOISE:-default}
JOBS=${JOBS:-2}
CONFIG=${CONFIG:-$ROOT/config/atlasd.toml}
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-sim atlas-replay atlas-eval atlas-render)
mkdir -p "$OUT"

one_run() {
  local kind=$1 seed=$2 dir=$OUT/$1/seed-$2
  mkdir -p "$dir"
  "$BIN/atlas-sim" --quiet --kind "$kind" --seed "$seed" --length-km "$LENGTH_KM" \
    --odometry-noise "$ODOMETRY_NOISE" --sonar none --out "$dir/sim"
  "$BIN/atlas-replay" --quiet --config "$CONFIG" \
    --reference "$dir/sim/truth.tsv" --out "$dir" "$dir/sim" >"$dir/replay.txt"
  "$ROOT/scripts/relations-from-reference.py" "$dir/reference.tsv" "$dir/all.relations" \
    --travel 1.0 --revisit-seconds 60
  "$ROOT/scripts/relations-from-reference.py" "$dir/reference.tsv" "$dir/returns.relations" \
    --revisit-seconds 60
  local set
  for set in all returns; do
    if [[ -s $dir/$set.relations ]]; then
      "$BIN/atlas-eval" --json --relations "$dir/$set.relations" --atlas "$dir" \
        --errors "$dir/${set}_errors.tsv" >"$dir/$set.json"
      "$BIN/atlas-eval" --json --relations "$dir/$set.relations" --dead-reckon "$dir/sim/run.clf" \
        >"$dir/${set}_odometry.json"
    fi
  done
}

n=0
for kind in $KINDS; do
  for seed in $SEEDS; do
    echo "eval-kinds: $kind seed $seed" >&2
    one_run "$kind" "$seed" &
    n=$((n + 1))
    if ((n % JOBS == 0)); then wait; fi
  done
done
wait

for kind in $KINDS; do
  first=${SEEDS%% *}
  dir=$OUT/$kind/seed-$first
  "$BIN/atlas-render" --run "$dir/sim" --png "$OUT/$kind-world.png" \
    --title "$kind, seed $first: world, truth, odometry, scans" || true
  "$BIN/atlas-render" --atlas "$dir" --whole --png "$OUT/$kind-atlas.png" \
    --title "$kind, seed $first: the atlas (Dijkstra projection from frame 0)" || true
done

echo "building kinds, odometry noise $ODOMETRY_NOISE, $CONFIG; relations metric, the atlas" \
  "along its Dijkstra paths, dead reckoning beside it"
echo "all: pose pairs 1 m apart and the returns; returns: pairs >= 60 s apart within 1.5 m;" \
  "ok: seeds where the atlas's mean over all relations is at most dead reckoning's"
"$ROOT/scripts/relations-summary.py" "$OUT" "$KINDS" $SEEDS
