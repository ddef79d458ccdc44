#!/usr/bin/env bash
# What atlas-view costs on the robot: its CPU and memory while atlasd maps on the fake devices
# and one browser watches. Not a ctest (it runs for minutes): run by hand inside a private
# network namespace (docs/atlas-view.md), with ATLASD, FAKEDEV, ATLAS_VIEW and DATASET set:
#
#   SECONDS_MEASURED=120 ATLASD=... FAKEDEV=... ATLAS_VIEW=.../atlas-view \
#     DATASET=.../mit-csail.clf.gz bash tests/hil/atlas_view_cost.sh
#
# atlas-fakedev plays the log at real time (SPEED, default 1); atlasd maps it with the shipped
# LCM periods (graph and hypotheses 1 s, local map 0.2 s, health 1 s); atlas-view runs with its
# defaults (4 updates/s at most) and headless Chromium keeps its page open (one event stream).
# After a 15 s warm-up, utime + stime of atlas-view (/proc/PID/stat) over SECONDS_MEASURED
# seconds of wall time, in % of one core; its resident memory at the end and its peak (VmRSS,
# VmHWM); the updates sent and their mean size (atlas-view's status line); atlasd's CPU beside
# it for scale.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
: "${ATLAS_VIEW:?set ATLAS_VIEW to the atlas-view binary}"
CHROMIUM=${CHROMIUM:-$(command -v chromium || true)}
[ -n "$CHROMIUM" ] || { echo "SKIP: chromium is not installed" >&2; exit 77; }
MEASURED=${SECONDS_MEASURED:-120}
SPEED=${SPEED:-1}
write_config "$WORK/atlasd.toml" "$SPEED"
sed -i '/^republish_raw = true/d; /^health_period_s = 0.5/d' "$WORK/atlasd.toml"
"$ATLAS_VIEW" --address 127.0.0.1 --port 8080 --status-every 30 >"$WORK/view.out" 2>"$WORK/view.err" &
VIEW_PID=$!
PIDS+=("$VIEW_PID")
start_fakedev --speed "$SPEED"
start_atlasd "$WORK/atlasd.toml"
sleep 0.5
mkdir -p "$WORK/chromium-profile"
"$CHROMIUM" --headless=new --no-sandbox --disable-gpu --no-first-run --disable-extensions \
  --user-data-dir="$WORK/chromium-profile" --window-size=1280,800 http://127.0.0.1:8080/ \
  >/dev/null 2>"$WORK/chromium.err" &
CHROME_PID=$!
PIDS+=("$CHROME_PID")
sleep 15
kill -0 "$ATLASD_PID" || fail "atlasd died"
kill -0 "$VIEW_PID" || fail "atlas-view died"
read -r wall v a < <(cpu_seconds "$MEASURED" "$VIEW_PID" "$ATLASD_PID")
rss=$(awk '/^VmRSS/ { print $2 }' "/proc/$VIEW_PID/status")
hwm=$(awk '/^VmHWM/ { print $2 }' "/proc/$VIEW_PID/status")
snapshot=$(curl -sS http://127.0.0.1:8080/snapshot.json | wc -c)
frames=$(curl -sS http://127.0.0.1:8080/snapshot.json | grep -oE '"frames_total":[0-9]+' | cut -d: -f2)
stop_pid "$VIEW_PID" 1.5 || fail "atlas-view exited non-zero"
stop_pid "$ATLASD_PID" 2.0 || fail "atlasd exited non-zero"
grep -q "^atlas-view: streams=1 " "$WORK/view.err" || fail "the browser never held an event stream: $(cat "$WORK/view.err")"
status=$(grep -E '^atlas-view: streams=' "$WORK/view.err" | tail -n 1)
updates=$(sed -E 's/.* updates=([0-9]+).*/\1/' <<<"$status")
bytes=$(sed -E 's/.* update_bytes=([0-9]+).*/\1/' <<<"$status")
awk -v v="$v" -v a="$a" -v w="$wall" -v rss="$rss" -v hwm="$hwm" -v u="$updates" -v b="$bytes" -v s="$snapshot" \
  -v f="$frames" 'BEGIN {
  printf "atlas-view cpu: %.2f %% of one core over %.0f s; rss %.1f MiB (peak %.1f MiB); %d updates in the run, mean %d bytes; last snapshot %d bytes, %d frames\n",
         100 * v / w, w, rss / 1024, hwm / 1024, u, b, s, f
  printf "beside it: atlasd %.2f %% of one core\n", 100 * a / w }' | tee "$WORK/cost.txt"
