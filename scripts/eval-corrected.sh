#!/usr/bin/env bash
# Corrected logs: for each of the six Radish "corrected" logs, synthesise wheel
# odometry from the corrected poses (seeded, a calibrated base's noise: drivers/sim
# WheelOdometryNoiseOptions defaults), run atlas-replay, score the Dijkstra-projected global
# trajectory against the reference (atlas-eval --reference; dead reckoning of the same
# synthesised odometry beside it), and check every map-match edge against the reference
# (closures.tsv: chi-square 3 dof > 14.16 = false loop closure; per-axis 3 sigma and gross
# errors also counted), and score the robot's returns (revisits: reference pose pairs <= 1.5 m
# apart with >= 20 m of travel between them, composed along the atlas's Dijkstra path; "open"
# = more than 0.5 m off; "joined" = the atlas closed the loop there: one frame, neighbouring
# frames or a path through a map-match edge; "chain" = only along two or more Genesis edges).
# Also draws Fig. 7 (step time, dominant frame id) for one log.
#
# Usage: scripts/eval-corrected.sh [OUT]      (default OUT: /tmp/atlas-eval-corrected)
# Environment: ATLAS_BIN (directory of atlas-replay, atlas-eval, atlas-carmen, atlas-render;
# default <repo>/build/release/bin, built if missing), SEED (default 1), FIG7_LOG (default
# intel), FIG7_PNG (default OUT/fig7-<log>.png), REFINE=1 to also score global_refined.tsv,
# ODOMETRY_NOISE (default | realistic: the synthesised odometry's noise level, default default).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" out "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-/tmp/atlas-eval-corrected}
SEED=${SEED:-1}
ODOMETRY_NOISE=${ODOMETRY_NOISE:-default}
DATA=${ATLAS_DATA:-$ROOT/../shared/datasets/corrected}
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-replay atlas-eval atlas-carmen atlas-render)
FIG7_LOG=${FIG7_LOG:-intel}
FIG7_PNG=${FIG7_PNG:-$OUT/fig7-$FIG7_LOG.png}
mkdir -p "$OUT"
# The noise models: the synthesised odometry is the simulator's base (config/noise-simulator.toml
# [noise.odometry]); the scans are real, so the lines get the real laser's noise
# (config/atlasd.toml [noise.laser]: walls that are not straight, floors on the line sigmas).
# With the simulator's laser model the fit gate dropped most real walls (aces: 257 of 440 scans
# without a line). The atlas: capacity 10, 4 hypotheses, the other [atlas] keys the shipped
# file's.
NOISE=$OUT/noise.toml
{
  sed -n '/^\[noise.odometry\]/,/^\[/p' "$ROOT/config/noise-simulator.toml" | sed '$d'
  sed -n '/^\[noise.laser\]/,/^\[/p' "$ROOT/config/atlasd.toml" | sed '$d'
} >"$NOISE"
CONFIG_FLAG=(--config "$NOISE" --map-capacity 10 --max-hypotheses 4)
REFINE_FLAG=()
[[ ${REFINE:-0} == 1 ]] && REFINE_FLAG=(--refine)

for name in intel aces freiburg-079 freiburg-101 csail seattle; do
  log=$DATA/$name-corrected.log.gz
  if [[ ! -r $log ]]; then
    echo "eval-corrected: $log is missing; skipped" >&2
    continue
  fi
  range=()
  [[ $name == aces ]] && range=(--log-max-range 50)  # aces clamps its ranges at 50 m
  dir=$OUT/$name
  mkdir -p "$dir"
  echo "== $name: replaying" >&2
  "$BIN/atlas-replay" --quiet --corrected --seed "$SEED" --odometry-noise "$ODOMETRY_NOISE" \
    "${range[@]}" "${CONFIG_FLAG[@]}" \
    "${REFINE_FLAG[@]}" \
    --out "$dir" "$log" >"$dir/replay.txt"
  "$BIN/atlas-eval" --json --reference "$dir/reference.tsv" "$dir/global.tsv" >"$dir/eval.json"
  if [[ ${REFINE:-0} == 1 ]]; then
    "$BIN/atlas-eval" --json --reference "$dir/reference.tsv" "$dir/global_refined.tsv" \
      >"$dir/eval_refined.json"
  fi
  # Dead reckoning of the same synthesised odometry (same seed and noise), for scale.
  "$BIN/atlas-carmen" --corrected --dump-odometry --seed "$SEED" \
    --odometry-noise "$ODOMETRY_NOISE" "${range[@]}" \
    --out "$dir/odometry.tsv" "$log"
  "$BIN/atlas-eval" --json --reference "$dir/reference.tsv" "$dir/odometry.tsv" \
    >"$dir/eval_odometry.json"
  # Revisits: where the robot returns. Pose pairs of the reference at most 1.5 m apart with at
  # least 20 m of travel between them (the nearest earlier pose, one pair per 5 scans at most),
  # as relations; the atlas's relation is composed along the Dijkstra path between the two
  # poses' frames (atlas-eval --atlas), so a loop the atlas did not close shows as the error
  # accumulated around it. Dead reckoning on the same pairs for scale.
  "$ROOT/scripts/relations-from-reference.py" "$dir/reference.tsv" "$dir/revisits.relations"
  if [[ -s $dir/revisits.relations ]]; then
    "$BIN/atlas-eval" --json --relations "$dir/revisits.relations" --atlas "$dir" \
      --errors "$dir/revisits_errors.tsv" >"$dir/revisits.json"
    "$BIN/atlas-eval" --json --relations "$dir/revisits.relations" "$dir/odometry.tsv" \
      >"$dir/revisits_odometry.json"
  fi
done

python3 - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
print("corrected logs, synthesised odometry (seed %s); errors of the Dijkstra projection from "
      "frame 0 against the reference" % os.environ.get("SEED", "1"))
print("RPE: pose pairs 1 m of travel apart; ATE: after the best rigid alignment. False closure: "
      "map-match edge vs reference, chi2 3 dof > 14.16")
hdr = ("log", "scans", "frames", "mm-edges", "RPE m", "RPE deg", "ATE m", "ATE deg",
       "odo ATE m", "false(chi2)", "false(axis)", "gross")
print("%-13s %6s %6s %8s %7s %7s %7s %7s %9s %11s %11s %5s" % hdr)
total = {"checked": 0, "chi2": 0, "axis": 0, "gross": 0}
for name in ["intel", "aces", "freiburg-079", "freiburg-101", "csail", "seattle"]:
    d = os.path.join(out, name)
    try:
        s = json.load(open(os.path.join(d, "summary.json")))
        e = json.load(open(os.path.join(d, "eval.json")))
        o = json.load(open(os.path.join(d, "eval_odometry.json")))
    except (OSError, ValueError) as err:
        print("%-13s missing: %s" % (name, err))
        continue
    print("%-13s %6d %6d %8d %7.3f %7.2f %7.3f %7.2f %9.3f %11d %11d %5d" % (
        name, s["scans"], s["frames"], s["closures_checked"],
        e["rpe_translation_m"]["mean"], e["rpe_rotation_deg"]["mean"],
        e["ate_translation_m"]["rmse"], e["ate_rotation_deg"]["rmse"],
        o["ate_translation_m"]["rmse"], s["false_closures_chi2"], s["false_closures_axis"],
        s["gross_closures"]))
    r = os.path.join(d, "eval_refined.json")
    if os.path.exists(r):
        er = json.load(open(r))
        print("%-13s %6s %6s %8s %7.3f %7.2f %7.3f %7.2f   (refined)" % (
            "", "", "", "", er["rpe_translation_m"]["mean"], er["rpe_rotation_deg"]["mean"],
            er["ate_translation_m"]["rmse"], er["ate_rotation_deg"]["rmse"]))
    total["checked"] += s["closures_checked"]
    total["chi2"] += s["false_closures_chi2"]
    total["axis"] += s["false_closures_axis"]
    total["gross"] += s["gross_closures"]
print("revisits: reference pose pairs <= 1.5 m apart with >= 20 m of travel between them; "
      "relation error composed along the atlas's Dijkstra path (dead reckoning beside it); "
      "open: pairs more than 0.5 m off; joined: the two poses share a frame, lie in "
      "neighbouring frames or are joined through a map-match edge (the loop is closed there); "
      "chain: joined only along two or more Genesis or refined edges")
print("%-13s %8s %9s %9s %6s %9s %9s %7s %5s %6s %5s" % (
    "log", "revisits", "atlas m", "atlas deg", "open", "odo m", "odo deg", "joined", "open",
    "chain", "open"))
for name in ["intel", "aces", "freiburg-079", "freiburg-101", "csail", "seattle"]:
    d = os.path.join(out, name)
    try:
        rv = json.load(open(os.path.join(d, "revisits.json")))
        ro = json.load(open(os.path.join(d, "revisits_odometry.json")))
        rows = [l.split() for l in open(os.path.join(d, "revisits_errors.tsv"))
                if not l.startswith("#")]
        errs = [float(r[2]) for r in rows]
    except (OSError, ValueError):
        print("%-13s %8s" % (name, "none"))
        continue
    chain = [float(r[2]) for r in rows if r[4] == "chain"]
    joined = [float(r[2]) for r in rows if r[4] != "chain"]
    print("%-13s %8d %9.3f %9.2f %6d %9.3f %9.2f %7d %5d %6d %5d" % (
        name, rv["matched"], rv["translation_m"]["mean"], rv["rotation_deg"]["mean"],
        sum(e > 0.5 for e in errs), ro["translation_m"]["mean"], ro["rotation_deg"]["mean"],
        len(joined), sum(e > 0.5 for e in joined), len(chain), sum(e > 0.5 for e in chain)))
print("all logs: %(checked)d map-match edges checked, %(chi2)d false closures (chi2), "
      "%(axis)d beyond 3 sigma on an axis, %(gross)d gross (> 0.5 m or 5 deg)" % total)
PY

if [[ -d $OUT/$FIG7_LOG ]]; then
  "$BIN/atlas-render" --atlas "$OUT/$FIG7_LOG" --timeline --png "$FIG7_PNG" \
    --title "$FIG7_LOG-corrected (synthesised odometry): step time and dominant map-frame id (Fig. 7)"
fi
# When the robot returns to a mapped place and is relocalised there, the dominant frame id falls
# back below the newest frame id (Fig. 7): how far, per log.
python3 - "$OUT" <<'PY'
import os, sys
for name in ["intel", "aces", "freiburg-079", "freiburg-101", "csail", "seattle"]:
    path = os.path.join(sys.argv[1], name, "timing.tsv")
    if not os.path.exists(path):
        continue
    rows = [l.split() for l in open(path) if not l.startswith("#")]
    behind = [int(r[2]) - 1 - int(r[4]) for r in rows if int(r[4]) >= 0]
    print("Fig. 7 %-13s dominant frame up to %d frames older than the newest; %d of %d steps "
          "more than 5 behind, %d more than 20 behind" % (
              name, max(behind, default=0), sum(b > 5 for b in behind), len(rows),
              sum(b > 20 for b in behind)))
PY
