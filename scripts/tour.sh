#!/usr/bin/env bash
# A tour of the real logs (docs/results.md, "A tour of the real logs"): the six corrected logs
# (odometry synthesised at ODOMETRY_NOISE, seed SEED; aces read with its 50 m no-return value)
# and mit-csail, one after another as one run through one atlas (atlas-carmen --dump-carmen
# --append: each log goes on 1 s after the last, its odometry moved to start where the last
# ended), then replayed and timed as scripts/constant-time.sh times a simulated run: the
# median step time over the first and the last tenth of the steps (target: within 15 %) and
# the largest step against the 10 ms budget, CPU and wall time, REPEAT replays. Buildings and
# lasers differ in cost (mit-csail's 361 beams against intel's 180), so the first and last
# tenths compare buildings as much as the atlas's size; the growth of the atlas is the ratio,
# per log, of its median step in the tour to its median step replayed alone (the same lines,
# OUT/logs/NAME.log), printed last.
#
# Usage: scripts/tour.sh [OUT]       (default OUT: /tmp/atlas-tour)
# Environment: ATLAS_BIN, ATLAS_DATA (default <repo>/../shared/datasets), SEED (1),
# ODOMETRY_NOISE (default | realistic), REPEAT (2), REPLAY_ARGS (default "--config
# config/atlasd.toml").
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" out "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-/tmp/atlas-tour}
DATA=${ATLAS_DATA:-$ROOT/../shared/datasets}
SEED=${SEED:-1}
ODOMETRY_NOISE=${ODOMETRY_NOISE:-default}
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-carmen atlas-sim atlas-replay atlas-render)
mkdir -p "$OUT"
TOUR=$OUT/tour.log
rm -f "$TOUR"
rm -rf "$OUT/logs" "$OUT/alone"
mkdir -p "$OUT/logs" "$OUT/alone"
NAMES=(intel aces freiburg-079 freiburg-101 csail seattle mit-csail)
echo "== writing the tour $TOUR" >&2
for name in "${NAMES[@]}"; do
  args=(--corrected --seed "$SEED" --odometry-noise "$ODOMETRY_NOISE")
  log=$DATA/corrected/$name-corrected.log.gz
  [[ $name == aces ]] && args+=(--log-max-range 50)  # aces clamps its ranges at 50 m
  [[ $name == mit-csail ]] && args=() log=$DATA/mit-csail/mit-csail.clf.gz
  "$BIN/atlas-carmen" --dump-carmen --append --out "$TOUR" "${args[@]}" "$log"
  "$BIN/atlas-carmen" --dump-carmen --out "$OUT/logs/$name.log" "${args[@]}" "$log" 2>/dev/null
done
cd "$ROOT"
REPLAY_ARGS=${REPLAY_ARGS:---config config/atlasd.toml}
ATLAS_BIN=$BIN LOG=$TOUR TITLE="tour of the six corrected logs and mit-csail" \
  REPLAY_ARGS=$REPLAY_ARGS scripts/constant-time.sh "$OUT"
read -r -a replay_args <<<"$REPLAY_ARGS"
for name in "${NAMES[@]}"; do
  "$BIN/atlas-replay" "${replay_args[@]}" --quiet --out "$OUT/alone/$name" "$OUT/logs/$name.log" \
    >/dev/null
done

python3 - "$OUT" "${NAMES[@]}" <<'PY'
import os, sys
out, names = sys.argv[1], sys.argv[2:]
def cpu(d):
    return [int(l.split()[1]) for l in open(os.path.join(d, "step_cpu.tsv"))
            if not l.startswith("#")]
def median(v):
    v = sorted(v)
    return v[len(v) // 2]
tour = cpu(os.path.join(out, "replay"))
for d in sorted(os.listdir(out)):
    if d.startswith("replay-"):
        other = cpu(os.path.join(out, d))
        if len(other) == len(tour):
            tour = [min(a, b) for a, b in zip(tour, other)]
print("  per log: median step CPU in the tour (least of the replays) against the log replayed alone")
first = 0
worst = 0.0
for name in names:
    alone = cpu(os.path.join(out, "alone", name))
    part = tour[first:first + len(alone)]
    first += len(alone)
    ratio = median(part) / median(alone)
    worst = max(worst, ratio)
    print("    %-13s %5d steps  tour %7.1f us  alone %7.1f us  tour/alone %.3f" % (
        name, len(alone), median(part) / 1e3, median(alone) / 1e3, ratio))
if first != len(tour):
    sys.exit("tour.sh: the tour stepped %d scans, the logs alone %d" % (len(tour), first))
print("  largest tour/alone %.3f (target within 15 %%: %s)" % (
    worst, "met" if worst <= 1.15 else "MISSED"))
PY
