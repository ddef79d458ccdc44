#!/usr/bin/env bash
# `atlasd --replay LOG` and `atlas-replay LOG` are one replay (replay/replay_run.h): with the same
# configuration file they write the same files, byte for byte, except what is measured while
# stepping (docs/formats.md, "Replay output"): step_ns in timing.tsv, step_cpu.tsv, and the
# wall-clock, CPU and memory figures of summary.json. Exit 77 (skip) without the dataset.
set -euo pipefail
: "${ATLASD:?}" "${ATLAS_REPLAY:?}" "${CONFIG:?}" "${DATASET:?}"
if [ ! -r "$DATASET" ]; then
  echo "SKIP: $DATASET is absent"
  exit 77
fi
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

"$ATLAS_REPLAY" --quiet --config "$CONFIG" --out "$WORK/tool" "$DATASET" >"$WORK/tool.out" ||
  fail "atlas-replay failed"
"$ATLASD" --replay "$DATASET" --config "$CONFIG" --out "$WORK/daemon" 2>"$WORK/daemon.err" ||
  fail "atlasd --replay failed: $(tail -n 3 "$WORK/daemon.err")"

tool_files=$(cd "$WORK/tool" && ls)
daemon_files=$(cd "$WORK/daemon" && ls)
[ "$tool_files" = "$daemon_files" ] ||
  fail "different files: atlas-replay wrote $(echo $tool_files), atlasd --replay $(echo $daemon_files)"
measured='"(wall_seconds|speedup|step_ns_median|step_ns_max|overruns|step_cpu_ns_median|step_cpu_ns_max|max_rss_kb|rss_kb_before_steps|rss_kb_after_steps)": [^,}]*'
for f in $tool_files; do
  case $f in
    timing.tsv) strip() { cut -f 1-5 "$1"; } ;;
    step_cpu.tsv) strip() { cut -f 1 "$1"; } ;;
    summary.json) strip() { sed -E "s/$measured/\"\\1\": measured/g" "$1"; } ;;
    *) strip() { cat "$1"; } ;;
  esac
  cmp -s <(strip "$WORK/tool/$f") <(strip "$WORK/daemon/$f") || {
    diff <(strip "$WORK/tool/$f") <(strip "$WORK/daemon/$f") | head -n 5 >&2
    fail "$f differs between atlas-replay and atlasd --replay"
  }
done
rows=$(grep -vc '^#' "$WORK/tool/trajectory.tsv")
[ "$rows" -gt 1000 ] || fail "only $rows trajectory rows"
echo "PASS: $(echo $tool_files | wc -w) files identical ($rows trajectory rows)"
