#!/usr/bin/env bash
# Regenerates the figures of docs/results.md. Each part runs its commands and rewrites its own
# block of the page (between `<!-- results:PART -->` and `<!-- /results:PART -->`); the blocks of
# parts not run keep their figures. The page's text outside the blocks is not touched.
#
# Usage: scripts/results.sh [--corrected] [--seeds] [--constant-time] [--tour] [--sonar] [--all]
#                           [--out DIR]
#   always:          mit-csail (accuracy against the relations, Dijkstra-composed and refined;
#                    the laser time offset sweep) and speed (five replays); about a minute
#   --corrected      the six corrected logs, seed 1 (scripts/eval-corrected.sh; minutes)
#   --seeds          the six corrected logs over seeds 1-10 (scripts/eval-corrected-seeds.sh;
#                    tens of minutes on two cores)
#   --constant-time  the 25 km simulated run (scripts/constant-time.sh; several minutes)
#   --tour           the six corrected logs and mit-csail as one run (scripts/tour.sh; a minute)
#   --sonar          sonar-only maps and atlases on the simulator (scripts/eval-sonar.sh; about
#                    25 minutes on two cores)
#   --all            every part
#   --out DIR        where the runs write (default /tmp/atlas-results)
# Environment: ATLAS_BIN (directory of the tools; default <repo>/build/release/bin, built if
# missing), ATLAS_DATA (default <repo>/../shared/datasets), RESULTS_PAGE (default
# <repo>/docs/results.md).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" any "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=/tmp/atlas-results
CORRECTED=0 SEEDS=0 CONSTANT=0 TOUR=0 SONAR=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --corrected) CORRECTED=1 ;;
    --seeds) SEEDS=1 ;;
    --constant-time) CONSTANT=1 ;;
    --tour) TOUR=1 ;;
    --sonar) SONAR=1 ;;
    --all) CORRECTED=1 SEEDS=1 CONSTANT=1 TOUR=1 SONAR=1 ;;
    --out)
      [[ $# -ge 2 ]] || { echo "results.sh: --out needs a directory" >&2; exit 2; }
      OUT=$2
      shift
      ;;
    *) echo "results.sh: unknown option '$1' (see scripts/results.sh --help)" >&2; exit 2 ;;
  esac
  shift
done
DATA=${ATLAS_DATA:-$ROOT/../shared/datasets}
PAGE=${RESULTS_PAGE:-$ROOT/docs/results.md}
LOG=$DATA/mit-csail/mit-csail.clf.gz
RELATIONS=$DATA/mit-csail/mit-csail.relations
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-replay atlas-eval)
[[ -r $LOG && -r $RELATIONS ]] || { echo "results.sh: $LOG or $RELATIONS is missing" >&2; exit 1; }
mkdir -p "$OUT"
FRAGMENTS=$OUT/fragments
rm -rf "$FRAGMENTS"
mkdir -p "$FRAGMENTS"
cd "$ROOT"

echo "== mit-csail: accuracy" >&2
rm -rf "$OUT/mit"
"$BIN/atlas-replay" --quiet --refine --config config/atlasd.toml --out "$OUT/mit" "$LOG" \
  >"$OUT/mit-replay.json"
"$BIN/atlas-eval" --json --relations "$RELATIONS" --atlas "$OUT/mit" >"$OUT/mit-composed.json"
"$BIN/atlas-eval" --json --relations "$RELATIONS" "$OUT/mit/global_refined.tsv" \
  >"$OUT/mit-refined.json"
echo "== mit-csail: laser time offset sweep" >&2
rm -rf "$OUT/sweep"
"$BIN/atlas-replay" --quiet --config config/atlasd.toml --sweep-laser-time-offset -0.3:0.1:0.02 \
  --out "$OUT/sweep" "$LOG" >/dev/null
python3 - "$OUT" "$FRAGMENTS/mit-csail.md" <<'PY'
import json, os, sys
out, frag = sys.argv[1], sys.argv[2]
summary = json.load(open(os.path.join(out, "mit", "summary.json")))
composed = json.load(open(os.path.join(out, "mit-composed.json")))
refined = json.load(open(os.path.join(out, "mit-refined.json")))
def row(name, j):
    t, r = j["translation_m"], j["rotation_deg"]
    return "| %s | %d | %.4f +- %.4f m | %.4f +- %.4f deg |" % (
        name, j["matched"], t["mean"], t["stddev"], r["mean"], r["stddev"])
best = ""
for line in open(os.path.join(out, "sweep", "sweep.tsv")):
    if line.startswith("# best:"):
        best = line[1:].strip()
with open(frag, "w") as f:
    f.write("""```sh
atlas-replay --refine --config config/atlasd.toml --out DIR mit-csail.clf.gz
atlas-eval --relations mit-csail.relations --atlas DIR
atlas-eval --relations mit-csail.relations DIR/global_refined.tsv
```

| estimate | relations | translational mean +- sd | rotational mean +- sd |
|---|---|---|---|
""")
    f.write(row("atlas, Dijkstra-composed (eq. 2-3)", composed) + "\n")
    f.write(row("atlas, refined (Ceres over the graph)", refined) + "\n")
    f.write("""
%d frames, %d map-match edges; the relations split into %d same-frame and %d cross-frame
(%d through a map-match edge, %d along a chain of Genesis edges). Target: 0.10 m and 1.0 deg.

Laser time offset (`atlas-replay --config config/atlasd.toml --sweep-laser-time-offset
-0.3:0.1:0.02 --out DIR mit-csail.clf.gz`): %s.
""" % (composed["frames"], summary.get("map_match_edges", summary.get("closures_checked", 0)),
       composed["same_frame"], composed["cross_frame"], composed["through_map_match"],
       composed["chain"], best or "no best line in sweep.tsv"))
PY

echo "== speed: five replays of mit-csail" >&2
python3 - "$BIN/atlas-replay" "$LOG" "$OUT" "$FRAGMENTS/speed.md" <<'PY'
import json, os, statistics, subprocess, sys, time
replay, log, out, frag = sys.argv[1:]
walls = []
for k in range(5):
    d = os.path.join(out, "speed")
    start = time.monotonic()
    subprocess.run([replay, "--quiet", "--out", d, log], check=True, stdout=subprocess.DEVNULL)
    walls.append(time.monotonic() - start)
data = json.load(open(os.path.join(out, "speed", "summary.json")))["data_seconds"]
median = statistics.median(walls)
with open(frag, "w") as f:
    f.write("""```sh
atlas-replay --quiet --out DIR mit-csail.clf.gz      # five runs, whole process, median
```

Wall time per run: %s s; median %.2f s for %.0f s of data: **%.0fx real time** (target 1000x).
The whole process is timed, reading the gzip log included; the machine's 1-minute load average
was %.1f at the end (on 2 cores), so on a busy machine the figure is low.
""" % (", ".join("%.2f" % w for w in walls), median, data, data / median, os.getloadavg()[0]))
PY

if [[ $CORRECTED == 1 ]]; then
  echo "== the six corrected logs, seed 1" >&2
  {
    echo '```sh'
    echo 'scripts/eval-corrected.sh OUT'
    echo '```'
    echo
    echo '```'
    scripts/eval-corrected.sh "$OUT/corrected"
    echo '```'
  } >"$FRAGMENTS/corrected.md"
fi

if [[ $SEEDS == 1 ]]; then
  echo "== the six corrected logs, seeds 1-10" >&2
  {
    echo '```sh'
    echo 'scripts/eval-corrected-seeds.sh OUT'
    echo '```'
    echo
    echo '```'
    scripts/eval-corrected-seeds.sh "$OUT/seeds"
    echo '```'
  } >"$FRAGMENTS/seeds.md"
fi

if [[ $CONSTANT == 1 ]]; then
  echo "== constant time: 25 km simulated run" >&2
  {
    echo '```sh'
    echo 'scripts/constant-time.sh OUT'
    echo '```'
    echo
    echo '```'
    scripts/constant-time.sh "$OUT/constant-time"
    echo '```'
  } >"$FRAGMENTS/constant-time.md"
  # The page's two pictures of the run, beside it.
  cp "$OUT/constant-time/constant-time-time.png" "$(dirname "$PAGE")/atlas-constant-time.png"
  cp "$OUT/constant-time/constant-time-frames.png" "$(dirname "$PAGE")/atlas-constant-time-frames.png"
fi

if [[ $TOUR == 1 ]]; then
  echo "== constant time: a tour of the real logs" >&2
  {
    echo '```sh'
    echo 'scripts/tour.sh OUT'
    echo '```'
    echo
    echo '```'
    scripts/tour.sh "$OUT/tour" | grep -v '^atlas-render: wrote'
    echo '```'
  } >"$FRAGMENTS/tour.md"
  cp "$OUT/tour/constant-time-time.png" "$(dirname "$PAGE")/atlas-tour-time.png"
fi

if [[ $SONAR == 1 ]]; then
  echo "== sonar-only maps and atlases on the simulator" >&2
  scripts/eval-sonar.sh "$OUT/sonar" >"$FRAGMENTS/sonar.md"
fi

python3 - "$PAGE" "$FRAGMENTS" <<'PY'
import os, re, sys
page, frags = sys.argv[1], sys.argv[2]
text = open(page).read()
for name in sorted(os.listdir(frags)):
    part = name[:-3]
    body = open(os.path.join(frags, name)).read()
    begin, end = "<!-- results:%s -->" % part, "<!-- /results:%s -->" % part
    if begin not in text or end not in text:
        sys.exit("results.sh: %s has no block %s ... %s" % (page, begin, end))
    a = text.index(begin) + len(begin)
    b = text.index(end)
    text = text[:a] + "\n" + body.rstrip("\n") + "\n" + text[b:]
    print("results.sh: %s rewritten" % part, file=sys.stderr)
open(page, "w").write(text)
PY
