#!/usr/bin/env bash
# Sonar-only maps and atlases on the simulator (docs/design.md, "Sonar local maps"), with
# atlasd's mapper defaults (atlas-sonar-eval):
# - the one-map check: `atlas-sonar-eval mc --runs 50 --minutes 4 --seed S [--ring 16]` over the
#   twenty seed blocks S = 1, 51, ..., 951 with 24 and 16 transducers: the robot NEES of the
#   sonar-only map against its 95 % band (the mean over the blocks of the share of steps inside
#   and of the mean NEES, the blocks at 95 % or more, the worst block);
# - the atlas: `atlas-sonar-eval atlas --laser 0 --runs 10 --seed S --ring R [--km 0.4 |
#   --world alcoves --km 0.5]` for S = 1, 11, ..., 191 (200 runs per cell) on the building and
#   the alcove loop with 24 and 16 transducers: the steps inside the robot NEES band (summed
#   over the twenty invocations), map-match edges, false closures (chi-square 3 dof > 14.16)
#   and gross ones (> 0.5 m or 5 deg).
# Prints a markdown fragment (the commands and two tables) on stdout, progress on stderr. The
# invocations run JOBS at a time under nice; about 25 minutes on two cores.
#
# Usage: scripts/eval-sonar.sh [OUT]            (default OUT: /tmp/atlas-eval-sonar)
# Environment: ATLAS_BIN (directory of atlas-sonar-eval; default <repo>/build/release/bin,
# built if missing), JOBS (default 2), PARTS (default "mc atlas": which of the two to run).
# Each invocation's output: OUT/mc-R-S.txt and OUT/atlas-WORLD-R-S.txt.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" out "$@"
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-/tmp/atlas-eval-sonar}
JOBS=${JOBS:-2}
PARTS=${PARTS:-mc atlas}
source "$ROOT/scripts/release-bin.sh"
BIN=$(release_bin atlas-sonar-eval)
mkdir -p "$OUT"
rm -f "$OUT"/mc-*.txt "$OUT"/atlas-*.txt

MC_SEEDS=$(seq 1 50 951)
ATLAS_SEEDS=$(seq 1 10 191)
jobs_file=$OUT/jobs.txt
: >"$jobs_file"
for ring in 24 16; do
  for s in $MC_SEEDS; do
    [[ " $PARTS " == *" mc "* ]] || continue
    echo "mc-$ring-$s.txt mc --runs 50 --minutes 4 --seed $s --ring $ring" >>"$jobs_file"
  done
done
for ring in 24 16; do
  for s in $ATLAS_SEEDS; do
    [[ " $PARTS " == *" atlas "* ]] || continue
    echo "atlas-building-$ring-$s.txt atlas --laser 0 --runs 10 --seed $s --ring $ring --km 0.4" \
      >>"$jobs_file"
    echo "atlas-alcoves-$ring-$s.txt atlas --laser 0 --runs 10 --seed $s --ring $ring" \
      "--world alcoves --km 0.5" >>"$jobs_file"
  done
done

# One invocation: its output file, then the tool's arguments.
run_one() {
  local out=$1
  shift
  nice "$BIN/atlas-sonar-eval" "$@" >"$OUT/$out" 2>/dev/null
}
total=$(wc -l <"$jobs_file")
k=0
running=0
while read -r out args; do
  k=$((k + 1))
  echo "eval-sonar: [$k/$total] atlas-sonar-eval $args" >&2
  # shellcheck disable=SC2086  # the arguments are words
  run_one "$out" $args &
  running=$((running + 1))
  if ((running >= JOBS)); then
    wait -n
    running=$((running - 1))
  fi
done <"$jobs_file"
while ((running > 0)); do
  wait -n
  running=$((running - 1))
done

python3 - "$OUT" "$PARTS" <<'PY'
import os, re, sys
out, parts = sys.argv[1], sys.argv[2].split()
mc_seeds = range(1, 952, 50)
atlas_seeds = range(1, 192, 10)

def read(name):
    return open(os.path.join(out, name)).read()

def match(pattern, text, name):
    m = re.search(pattern, text)
    if not m:
        sys.exit("eval-sonar.sh: %s has no line matching %r" % (name, pattern))
    return m

print("```sh")
if "mc" in parts:
    print("atlas-sonar-eval mc --runs 50 --minutes 4 --seed S [--ring 16]       # S = 1, 51, ..., 951")
if "atlas" in parts:
    print("atlas-sonar-eval atlas --laser 0 --runs 10 --seed S --ring R \\\n"
          "    [--km 0.4 | --world alcoves --km 0.5]                             # S = 1, 11, ..., 191")
print("```")


def mc_table():
    print("""
One map in the corridor, robot NEES of the sonar-only map (50 runs per block, 20 blocks):

| ring | 95 % band | mean NEES, mean over the blocks | steps inside the band, mean over the blocks | blocks at 95 % or more | worst block |
|---|---|---|---|---|---|""")
    for ring in (24, 16):
        inside, means = [], []
        band = None
        for s in mc_seeds:
            name = "mc-%d-%d.txt" % (ring, s)
            m = match(r"robot NEES sonar-only\s*: 95% band \[([\d.]+), ([\d.]+)\]; mean ([\d.]+), "
                      r"max [\d.]+; steps inside \d+/\d+ = ([\d.]+)%", read(name), name)
            band = (m.group(1), m.group(2))
            means.append(float(m.group(3)))
            inside.append(float(m.group(4)))
        print("| %d | [%s, %s] | %.2f | %.1f %% | %d of %d | %.1f %% |" % (
            ring, band[0], band[1], sum(means) / len(means), sum(inside) / len(inside),
            sum(1 for v in inside if v >= 95.0), len(inside), min(inside)))


def atlas_table():
    print("""
The atlas (200 runs per cell; steps inside the robot NEES band summed over the twenty
invocations, each against the band of its 10 runs' mean):

| world, ring | steps inside the NEES band | map-match edges | false closures (gross) |
|---|---|---|---|""")
    all_false = all_gross = runs = 0
    for world, label in (("building", "building"), ("alcoves", "alcove loop")):
        for ring in (24, 16):
            inside = steps = edges = false = gross = 0
            for s in atlas_seeds:
                name = "atlas-%s-%d-%d.txt" % (world, ring, s)
                text = read(name)
                m = match(r"robot NEES sonar-only .*steps inside (\d+)/(\d+) =", text, name)
                inside += int(m.group(1))
                steps += int(m.group(2))
                m = match(r"map-match edges vs ground truth: (\d+) edges, (\d+) false closures "
                          r"\(.*?\), (\d+) gross", text, name)
                edges += int(m.group(1))
                false += int(m.group(2))
                gross += int(m.group(3))
                runs += 10
            all_false += false
            all_gross += gross
            print("| %s, %d | %.1f %% | %d | %d (%d) |" % (
                label, ring, 100.0 * inside / max(steps, 1), edges, false, gross))
    print("\nAll cells: %d false closures (%d gross) in %d runs." % (all_false, all_gross, runs))


if "mc" in parts:
    mc_table()
if "atlas" in parts:
    atlas_table()
PY
