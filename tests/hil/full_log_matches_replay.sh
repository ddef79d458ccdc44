#!/usr/bin/env bash
# HIL (a): the whole mit-csail log played by atlas-fakedev at 4x real time (424 s of log in
# about 110 s) into a real atlasd; lcm-logger records ATLAS_POSE. The live result is scored on
# the benchmark's relations exactly as atlas-replay's result on the same log, and the two
# scores must agree within a small tolerance: the live path (ptys, CAN, threads, queues, LCM)
# loses nothing.
#
# Same mapper on both sides (one configuration file for both): map capacity 10, 4 hypotheses,
# probation 8, sigmas 0.5/0.5/0.2, 24 frames projected, 1 match candidate, range sigma 0.01 m,
# max range 8 m (atlasd's laser.max_range_m, applied by its laser reader; atlas-replay's
# --laser-max-range), and no scan is dropped (loop.max_pending_scans = 64). The odometry track
# width stays atlasd's default 0.58 m, the fake base's: the CAN wheel counters must be decoded
# with the width they were encoded with.
#
# Live stamps are this machine's monotonic arrival times, published as microseconds since the
# epoch: atlasd prints the offset ("LCM utime = CLOCK_MONOTONIC + O us"), and a pose's utime u is
# the monotonic stamp t = u - O. atlas-fakedev prints its clock mapping ("playing: log_start L
# monotonic_start M speed S"): a live stamp t is log time L + (t - M) * S, plus the delivery delay (the fake's and the driver's scheduling, times S:
# usually well under 1 ms of log time, tens of ms on a loaded machine). Each live pose is given
# the stamp of the next log scan in order that was sent before it arrived (5 ms of clock
# slack); if that one is more than 250 ms of log time old, scans were lost, and the last scan
# sent is taken instead; a pose with no unused scan sent in the 250 ms before it is counted and
# left out (a scan is used once). That stamp is the one atlas-replay gives the same
# scan, so atlas-eval pairs both with the relations the same way. The live graph is the atlas atlasd saved (atlasd --export-atlas).
#
# Checks: live stepped every scan replay stepped (within 1 %), at most 1 % of the poses left
# out by the stamp mapping, matched relation counts within 2 %, and mean translational /
# rotational relation errors within 0.5 m / 3 deg of replay's. The live run is not the same
# computation as the replay: its odometry comes from CAN wheel counters (1 mm steps, sent every
# 20 ms of log time) stamped at arrival, with the scheduling delays of a shared 2-core machine
# times the speed, and the atlas's discrete decisions (new frames, matches) amplify small
# differences. Runs on a loaded machine (load 8 to 9): replay 1.666 m / 5.29 deg, 67 frames, live
# 1.809 m / 6.36 deg, 73 frames; a later tree: replay 1.742 m / 5.30 deg, 68 frames, live
# 2.109 m / 7.89 deg, 78 frames (6 odometry messages counted bad). The tolerance comes from
# these few runs: the live path is close to replay, measurably worse under load at 4x, not
# identical.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
[ -f "$RELATIONS" ] || { echo "SKIP: $RELATIONS absent" >&2; exit 77; }
SPEED=4
# The noise models are config/noise-simulator.toml's (core/localmap's defaults), not the shipped B21 profile: with the B21 profile one run scored replay
# 1.37 m / 2.1 deg against live 2.66 m / 6.2 deg (loaded machine), beyond the
# tolerance below.
write_config "$WORK/atlasd.toml" "$SPEED" \
  "[atlas]" "map_capacity = 10" "max_hypotheses = 4" "probation_steps = 8" \
  "max_sigma_x = 0.5" "max_sigma_y = 0.5" "max_sigma_theta = 0.2" \
  "frames_examined_per_step = 24" "match_candidates_per_step = 1" "quality_alpha = 0.5" \
  "[loop]" "max_pending_scans = 64"
cat "$(dirname "$0")/../../config/noise-simulator.toml" >>"$WORK/atlasd.toml"
sed -i 's/^max_range_m = 50.0/max_range_m = 8.0/; s/^republish_raw = true/republish_raw = false/' \
  "$WORK/atlasd.toml"
"$ATLASD" --check-config "$WORK/atlasd.toml" >/dev/null 2>"$WORK/check.err" || fail "config: $(cat "$WORK/check.err")"

# Replay first (it also gives the scan stamps), while nothing else runs.
"$ATLAS_REPLAY" --config "$WORK/atlasd.toml" --laser-max-range 8 --out "$WORK/replay" --quiet "$DATASET" >"$WORK/replay.json" 2>"$WORK/replay.err" ||
  fail "atlas-replay failed: $(tail -n 3 "$WORK/replay.err")"

LCM_DEFAULT_URL="${LCM_DEFAULT_URL}&recv_buf_size=16777216" lcm-logger --quiet --channel ATLAS_POSE \
  "$WORK/session.lcm" >"$WORK/logger.err" 2>&1 &
LOGGER_PID=$!
PIDS+=("$LOGGER_PID")
sleep 0.3
start_fakedev --speed "$SPEED"
start_atlasd "$WORK/atlasd.toml" --health-every 10
for _ in $(seq 1500); do kill -0 "$FAKEDEV_PID" 2>/dev/null || break; sleep 0.1; done
kill -0 "$FAKEDEV_PID" 2>/dev/null && fail "atlas-fakedev still playing after 150 s"
sleep 2  # the loop steps what is pending
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero"
sleep 0.3
stop_logger
"$ATLASD" --config "$WORK/atlasd.toml" --export-atlas "$WORK/live" 2>"$WORK/export.err" ||
  fail "export: $(cat "$WORK/export.err")"
"$LOG_SUMMARY" "$WORK/session.lcm" --poses "$WORK/live_poses.txt" >"$WORK/summary.txt"

read -r L M S < <(sed -nE 's/^playing: log_start ([0-9.e+-]+) monotonic_start ([0-9.e+-]+) speed ([0-9.e+-]+)$/\1 \2 \3/p' \
  "$WORK/fakedev.out")
[ -n "${S:-}" ] || fail "atlas-fakedev printed no clock mapping"
O=$(sed -nE 's/^atlasd: LCM utime = CLOCK_MONOTONIC \+ (-?[0-9]+) us.*/\1/p' "$WORK/atlasd.err")
[ -n "$O" ] || fail "atlasd printed no epoch offset"
# live poses "t x y theta frame q" -> trajectory.tsv "stamp frame x y theta" on the scan stamps
# of the replay's timing.tsv ("step timestamp ...").
awk -v L="$L" -v M="$M" -v S="$S" -v O="$O" -v out="$WORK/live/trajectory.tsv" -v stats="$WORK/mapping.txt" '
  BEGIN { last = -1 }
  NR == FNR { if ($1 !~ /^#/) stamp[n++] = $2; next }
  $1 !~ /^#/ {
    t = L + ($1 - O * 1e-6 - M) * S + 0.005
    while (j < n && stamp[j] <= t) j++
    k = last + 1  # the next scan, if it was sent before this pose arrived
    if (k >= j || t - stamp[k] > 0.25) k = j - 1  # else the last one sent (scans lost)
    if (k <= last || t - stamp[k] > 0.25) { far++; next }
    last = k; kept++; d = t - 0.005 - stamp[k]; sum += d; if (d > dmax) dmax = d
    printf "%s\t%s\t%s\t%s\t%s\n", stamp[k], $5, $2, $3, $4 > out
  }
  END { printf "kept=%d far=%d mean_delay_log_s=%.6f max_delay_log_s=%.6f\n", kept, far,
        kept ? sum / kept : 0, dmax > stats }' "$WORK/replay/timing.tsv" "$WORK/live_poses.txt"
sed -i '1i # atlasd live poses on log scan stamps: timestamp frame x y theta' "$WORK/live/trajectory.tsv"
cat "$WORK/mapping.txt"
grep -E '^atlasd: up' "$WORK/atlasd.err" | tail -n 1
compare_with_replay live
