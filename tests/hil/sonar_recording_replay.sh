#!/usr/bin/env bash
# HIL: a sonar recording re-run. `sonar_recording_replay.sh MODE` (MODE: sonar or both, the
# [localmap] sensors value): atlas-sim makes a short run through a small building; atlas-fakedev
# plays it at 2x on the fake laser, CAN base and P2OS sonar (returns synthesised from the
# laser, drivers/fake/fake_p2os.h); atlasd maps it with the raw channels republished and
# lcm-logger records the session. Checks:
#   - atlasd published a pose for every range item its maps use (sonar: one per sonar reading
#     it stepped; both: readings and scans), with no pose gap over 0.5 s;
#   - MODE sonar: the poses follow the sonar readings at once (the sonar reader wakes the loop):
#     median from a reading's arrival stamp to its pose received by an LCM subscriber
#     (atlas-pose-latency) under 2 ms (measured 0.42 ms; with the loop woken only by the
#     laser at 4 Hz or its 10 ms idle wait, 3.5 ms);
#   - `atlasd --replay` of the recording with the same configuration file steps as many items
#     (timing.tsv) and gives the same poses: the n-th row of its trajectory.tsv has the stamp,
#     frame, x, y and theta (printed to 1e-6) of the n-th live pose with a frame.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
MODE=${1:?usage: sonar_recording_replay.sh sonar|both}
: "${SIM:?set SIM to the atlas-sim binary}" "${POSE_LATENCY:?set POSE_LATENCY}"
SPEED=2
# MODE sonar: the laser at 4 Hz, so that most readings (10 Hz) come without a scan to wake the
# loop; MODE both: both at 10 Hz, reading and scan arriving together (the fake P2OS sends a SIP
# every 0.1 s of log time, made from the latest scan): their order is the hard case for replay.
LASER_HZ=10
[ "$MODE" = sonar ] && LASER_HZ=4
"$SIM" --rooms 4 --length-km 0.01 --seed 5 --sonar p3dx --laser-hz "$LASER_HZ" --out "$WORK/sim" \
  --quiet || fail "atlas-sim failed"
DATASET=$WORK/sim/run.clf
# No scan is dropped live (replay drops none), so that the two step the same items.
write_config "$WORK/atlasd.toml" "$SPEED" "[localmap]" "sensors = \"$MODE\"" \
  "[loop]" "max_pending_scans = 64"
# write_config's laser section is for the recorded logs; the simulated laser: 30 m, 181 beams.
sed -i 's/^max_range_m = 50.0/max_range_m = 30.0\nangular_resolution_deg = 1.0/' "$WORK/atlasd.toml"
"$ATLASD" --check-config "$WORK/atlasd.toml" >/dev/null 2>"$WORK/check.err" || fail "config: $(cat "$WORK/check.err")"

start_logger
start_fakedev --speed "$SPEED"
start_atlasd "$WORK/atlasd.toml" --health-every 5
"$POSE_LATENCY" --seconds 8 --warmup 20 >"$WORK/latency.txt" 2>"$WORK/latency.err" &
LATENCY_PID=$!
PIDS+=("$LATENCY_PID")
for _ in $(seq 600); do kill -0 "$FAKEDEV_PID" 2>/dev/null || break; sleep 0.1; done
kill -0 "$FAKEDEV_PID" 2>/dev/null && fail "atlas-fakedev still playing after 60 s"
wait "$LATENCY_PID" || true
sleep 0.5  # the loop steps what is pending
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero"
sleep 0.3
stop_logger
"$LOG_SUMMARY" "$WORK/session.lcm" --poses "$WORK/live_poses.txt" >"$WORK/summary.txt"
S="$WORK/summary.txt"
steps=$(summary_value "$S" health.last_steps)
readings=$(summary_value "$S" events.ATLAS_RAW_SONAR)
scans=$(summary_value "$S" events.ATLAS_RAW_LASER)
gap=$(summary_value "$S" pose.max_gap_s)
dropped=$(summary_value "$S" health.dropped_scans)
echo "live: $steps steps, $readings sonar readings and $scans scans recorded, max pose gap $gap s, dropped $dropped"
[ "${readings:-0}" -gt 100 ] || fail "only '$readings' raw sonar readings recorded"
want=$readings
[ "$MODE" = both ] && want=$((readings + scans))
# The last health message may be up to a health period old.
[ "$steps" -le "$want" ] && [ "$steps" -ge $((want * 9 / 10)) ] ||
  fail "atlasd stepped $steps items, the maps use $want"
awk -v g="$gap" 'BEGIN { exit !(g < 0.5) }' || fail "ATLAS_POSE stopped for $gap s"

if [ "$MODE" = sonar ]; then
  cat "$WORK/latency.txt"
  median=$(sed -nE 's/.*median_us=([0-9.]+).*/\1/p' "$WORK/latency.txt")
  [ -n "$median" ] || fail "atlas-pose-latency printed nothing: $(cat "$WORK/latency.err")"
  awk -v m="$median" 'BEGIN { exit !(m < 2000) }' ||
    fail "median sonar reading -> pose $median us: the loop is not woken by the sonar"
fi

"$ATLASD" --replay "$WORK/session.lcm" --out "$WORK/replay" --config "$WORK/atlasd.toml" \
  2>"$WORK/replay.err" || fail "atlasd --replay failed: $(tail -n 3 "$WORK/replay.err")"
tail -n 1 "$WORK/replay.err"
# The replay's poses against the live poses in the order published (the step order), leaving
# out live's dead-reckoning poses (odometry stamps, before the first range item) and the steps
# without a dominant hypothesis (frame -1 live; no trajectory.tsv row): two items of the same
# microsecond (a scan and a reading) are compared in order too. The steps are timing.tsv's rows.
awk 'FILENAME == ARGV[1] { if ($1 !~ /^#/) steps++; next }
  FILENAME == ARGV[2] { if ($1 !~ /^#/) { rep[n++] = $0; step[$1] = 1 } next }
  ($1 in step) && $5 >= 0 {
    if (k >= n) { extra++; next }
    split(rep[k++], r, "\t")
    if (r[1] != $1 || r[2] != $5 || r[3] != $2 || r[4] != $3 || r[5] != $4) {
      differ++
      if (differ <= 3) printf "differs at row %d: live %s | replay %s\n", k, $0, rep[k - 1]
    }
  }
  END { printf "replay_steps=%d missing_live=%d differ=%d\n", steps, n - k + extra, differ }' \
  "$WORK/replay/timing.tsv" "$WORK/replay/trajectory.tsv" "$WORK/live_poses.txt" |
  tee "$WORK/compare.txt"
read -r rsteps missing differ < <(sed -nE 's/^replay_steps=([0-9]+) missing_live=([0-9]+) differ=([0-9]+)$/\1 \2 \3/p' "$WORK/compare.txt")
[ "$rsteps" -eq "$want" ] || fail "replay stepped $rsteps items, the log holds $want the maps use"
[ "$missing" -eq 0 ] && [ "$differ" -eq 0 ] ||
  fail "replay differs from live: $missing steps without a live pose (or the reverse), $differ poses differ"
pass "sensors = $MODE: live $steps steps ($readings sonar readings, $scans scans); replay $rsteps steps, every pose with a frame equal to live"
