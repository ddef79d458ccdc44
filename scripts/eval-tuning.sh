#!/usr/bin/env bash
# The tuning set's corrected logs (intel and freiburg-079 by default; issue 32's generalisation
# discipline keeps the other corrected logs and mit-csail for reporting a decided change) over
# odometry seeds, with one configuration file, scored as scripts/eval-kinds.sh scores the
# simulator: per log and seed, atlas-replay --corrected --config CONFIG, relations from the
# reference at the scans (pose pairs 1 m of travel apart plus the returns: the nearest earlier
# pose within 1.5 m after at least 20 m of travel), the atlas's relations composed along its
# Dijkstra paths (atlas-eval --atlas) and dead reckoning of the same synthesised odometry on the
# same relations (atlas-carmen --dump-odometry). One line per log: mean error over all
# relations (atlas, odometry; seeds where the atlas is no worse), mean error on the returns,
# false closures (chi2 3 dof > 14.16), returns joined, and the step time (median of the seeds'
# medians, largest max, ms of CPU).
#
# Usage: scripts/eval-tuning.sh [OUT]      (default OUT: /tmp/atlas-eval-tuning)
# Environment: LOGS (default "intel freiburg-079"; aces is read with its 50 m no-return value),
# SEEDS (default "1 2 3"), ODOMETRY_NOISE (default | realistic), CONFIG (default
# <repo>/config/atlasd.toml), JOBS (default 2), ATLAS_BIN and ATLAS_DATA as for
# scripts/eval-corrected.sh.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" out "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-/tmp/atlas-eval-tuning}
LOGS=${LOGS:-intel freiburg-079}
SEEDS=${SEEDS:-1 2 3}
ODOMETRY_NOISE=${ODOMETRY_NOISE:-default}
CONFIG=${CONFIG:-$ROOT/config/atlasd.toml}
JOBS=${JOBS:-2}
DATA=${ATLAS_DATA:-$ROOT/../shared/datasets/corrected}
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-replay atlas-eval atlas-carmen)
mkdir -p "$OUT"

one_run() {
  local name=$1 seed=$2 dir=$OUT/$1/seed-$2 log=$DATA/$1-corrected.log.gz range=()
  [[ $name == aces ]] && range=(--log-max-range 50)  # aces clamps its ranges at 50 m
  mkdir -p "$dir"
  "$BIN/atlas-replay" --quiet --corrected --seed "$seed" --odometry-noise "$ODOMETRY_NOISE" \
    "${range[@]}" --config "$CONFIG" --out "$dir" "$log" >"$dir/replay.txt"
  "$BIN/atlas-carmen" --corrected --dump-odometry --seed "$seed" \
    --odometry-noise "$ODOMETRY_NOISE" "${range[@]}" --out "$dir/odometry.tsv" "$log"
  "$ROOT/scripts/relations-from-reference.py" "$dir/reference.tsv" "$dir/all.relations" \
    --travel 1.0
  "$ROOT/scripts/relations-from-reference.py" "$dir/reference.tsv" "$dir/returns.relations"
  local set
  for set in all returns; do
    if [[ -s $dir/$set.relations ]]; then
      "$BIN/atlas-eval" --json --relations "$dir/$set.relations" --atlas "$dir" \
        --errors "$dir/${set}_errors.tsv" >"$dir/$set.json"
      "$BIN/atlas-eval" --json --relations "$dir/$set.relations" "$dir/odometry.tsv" \
        >"$dir/${set}_odometry.json"
    fi
  done
}

n=0
for name in $LOGS; do
  for seed in $SEEDS; do
    echo "eval-tuning: $name seed $seed" >&2
    one_run "$name" "$seed" &
    n=$((n + 1))
    if ((n % JOBS == 0)); then wait; fi
  done
done
wait

echo "corrected logs, odometry noise $ODOMETRY_NOISE, $CONFIG; relations metric, the atlas" \
  "along its Dijkstra paths, dead reckoning beside it"
"$ROOT/scripts/relations-summary.py" "$OUT" "$LOGS" $SEEDS
