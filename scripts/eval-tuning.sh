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
# Environment: LOGS (default "intel freiburg-079"), SEEDS (default "1 2 3"), ODOMETRY_NOISE
# (default | realistic), CONFIG (default <repo>/config/atlasd.toml), JOBS (default 2), ATLAS_BIN
# and ATLAS_DATA as for scripts/eval-corrected.sh.
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
  local name=$1 seed=$2 dir=$OUT/$1/seed-$2 log=$DATA/$1-corrected.log.gz
  mkdir -p "$dir"
  "$BIN/atlas-replay" --quiet --corrected --seed "$seed" --odometry-noise "$ODOMETRY_NOISE" \
    --config "$CONFIG" --out "$dir" "$log" >"$dir/replay.txt"
  "$BIN/atlas-carmen" --corrected --dump-odometry --seed "$seed" \
    --odometry-noise "$ODOMETRY_NOISE" -o "$dir/odometry.tsv" "$log"
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

python3 - "$OUT" "$ODOMETRY_NOISE" "$CONFIG" "$LOGS" $SEEDS <<'PY'
import json, os, statistics, sys
out, noise, config, logs, seeds = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split(), sys.argv[5:]
def load(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return None
print("corrected logs, %d seeds each, odometry noise %s, %s; relations metric, the atlas along "
      "its Dijkstra paths, dead reckoning beside it" % (len(seeds), noise, config))
hdr = ("log", "seeds", "atlas m", "atlas deg", "odo m", "odo deg", "ok", "ret atlas m",
       "ret odo m", "false", "joined", "step ms", "max ms")
print("%-13s %5s %8s %9s %7s %7s %5s %11s %9s %5s %11s %7s %7s" % hdr)
for name in logs:
    rows, ok, false, joined, returns, ret, med, mx = [], 0, 0, 0, 0, [], [], []
    for s in seeds:
        d = os.path.join(out, name, "seed-" + s)
        a, o = load(os.path.join(d, "all.json")), load(os.path.join(d, "all_odometry.json"))
        summary = load(os.path.join(d, "summary.json"))
        if not a or not o or not summary:
            continue
        rows.append((a["translation_m"]["mean"], a["rotation_deg"]["mean"],
                     o["translation_m"]["mean"], o["rotation_deg"]["mean"]))
        ok += a["translation_m"]["mean"] <= o["translation_m"]["mean"]
        false += summary.get("false_closures_chi2", 0)
        med.append(summary["step_cpu_ns_median"] * 1e-6)
        mx.append(summary["step_cpu_ns_max"] * 1e-6)
        ra, ro = load(os.path.join(d, "returns.json")), load(os.path.join(d, "returns_odometry.json"))
        if ra and ro:
            ret.append((ra["translation_m"]["mean"], ro["translation_m"]["mean"]))
            errors = [l.split() for l in open(os.path.join(d, "returns_errors.tsv"))
                      if not l.startswith("#")]
            returns += sum(1 for _ in open(os.path.join(d, "returns.relations")))
            joined += sum(1 for e in errors if len(e) > 4 and e[4] != "chain")
    if not rows:
        print("%-13s %5s" % (name, "none"))
        continue
    mean = lambda k, v: sum(r[k] for r in v) / len(v)
    print("%-13s %5d %8.3f %9.2f %7.3f %7.2f %5s %11s %9s %5d %11s %7.2f %7.2f" % (
        name, len(rows), mean(0, rows), mean(1, rows), mean(2, rows), mean(3, rows),
        "%d/%d" % (ok, len(rows)),
        "%.3f" % mean(0, ret) if ret else "-", "%.3f" % mean(1, ret) if ret else "-",
        false, "%d/%d" % (joined, returns), statistics.median(med), max(mx)))
PY
