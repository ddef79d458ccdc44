#!/usr/bin/env bash
# HIL: atlasd's LCM input (input.source = "lcm") maps a recording played on LCM to the poses
# atlas-replay computes from the same recording. Usage: lcm_input_matches_replay.sh [TYPES]
# (atlas, the default, or bot_core: the played file is then in libbot's types). The first MAX_SCANS scans of mit-csail are
# converted by atlas-carmen-to-lcm into an lcm-logger file of atlasd.laser_scan_t and
# atlasd.odometry_t (the odometry interpolated at 50 Hz, as a base sends it), which lcm-logplayer
# plays at SPEED times real time into atlasd in a private network namespace; lcm-logger records
# ATLAS_POSE, ATLAS_HEALTH and the scans as atlasd received them. atlas-replay replays the same
# file with the same configuration and atlasd's laser range (laser.max_range_m, which the LCM
# input applies to the scans it receives: --laser-max-range 8).
#
# atlasd stamps each message with its arrival time; each live pose is given the log stamp
# (utime) of the scan it was computed from: the next scan in order that the logger received
# before the pose (5 ms of slack; if that one is more than 250 ms of log time older, scans were
# lost and the last one received is taken; a pose with no unused scan received in the 250 ms
# of log time before it is counted and left out). atlas-replay gives the same scan the same
# stamp, so atlas-eval pairs both with the relations the same way.
#
# Checks: no scan dropped anywhere (the LCM input's queues, the loop) and none bad, atlasd
# stepped every scan played, at most 1 % of the poses left out by the mapping, matched relation
# counts within 2 %, and mean relation errors within 0.5 m / 3 deg of replay's: the live run
# differs from the replay only by the arrival stamps (scheduling delays times SPEED) and the
# atlas's discrete decisions that amplify them. One pose per run is left out: it is published
# before the first scan (dead reckoning on the first odometry). Figures: docs/journal/atlasd.md.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
[ -f "$RELATIONS" ] || { echo "SKIP: $RELATIONS absent" >&2; exit 77; }
command -v lcm-logplayer >/dev/null || { echo "SKIP: lcm-logplayer (liblcm-bin) absent" >&2; exit 77; }
SPEED=${SPEED:-4}
MAX_SCANS=${MAX_SCANS:-1200}
# atlas: atlasd's own laser_scan_t and odometry_t; bot_core: libbot's planar_lidar_t and pose_t
# (the same data; the scanner's mount, 0 in mit-csail, and the maximum range from the file).
TYPES=${1:-atlas}

# The mapper of tests/hil/full_log_matches_replay.sh, on the LCM input.
cat >"$WORK/atlasd.toml" <<TOML
# LCM input test configuration (written by tests/hil/lcm_input_matches_replay.sh)
[input]
source = "lcm"
$([ "$TYPES" = bot_core ] && printf 'laser_type = "bot_core.planar_lidar_t"\nodometry_type = "bot_core.pose_t"')
[laser]
max_range_m = 8.0
[laser.mount]
x_m = 0.0
[lcm]
url = "${LCM_DEFAULT_URL}"
health_period_s = 0.5
[state]
directory = "$WORK/state"
[atlas]
map_capacity = 10
max_hypotheses = 4
probation_steps = 8
max_sigma_x = 0.5
max_sigma_y = 0.5
max_sigma_theta = 0.2
frames_examined_per_step = 24
match_candidates_per_step = 1
quality_alpha = 0.5
[loop]
max_pending_scans = 64
TOML
cat "$(dirname "$0")/../../config/noise-simulator.toml" >>"$WORK/atlasd.toml"
"$ATLASD" --check-config "$WORK/atlasd.toml" >/dev/null 2>"$WORK/check.err" || fail "config: $(cat "$WORK/check.err")"

# The replay reads atlasd's own types; with bot_core the same events are played in libbot's.
"$CARMEN_TO_LCM" "$DATASET" --out "$WORK/replay.lcm" --max-scans "$MAX_SCANS" >"$WORK/convert.out" \
  2>"$WORK/convert.err" || fail "atlas-carmen-to-lcm failed"
"$CARMEN_TO_LCM" "$DATASET" --out "$WORK/play.lcm" --max-scans "$MAX_SCANS" --types "$TYPES" \
  >/dev/null 2>"$WORK/convert.err" || fail "atlas-carmen-to-lcm --types $TYPES failed"
scans=$(sed -E 's/^scans=([0-9]+).*/\1/' "$WORK/convert.out")
echo "played: $(cat "$WORK/convert.out")"

"$ATLAS_REPLAY" --config "$WORK/atlasd.toml" --laser-max-range 8 --out "$WORK/replay" --quiet "$WORK/replay.lcm" \
  >"$WORK/replay.json" 2>"$WORK/replay.err" || fail "atlas-replay failed: $(tail -n 3 "$WORK/replay.err")"

LCM_DEFAULT_URL="${LCM_DEFAULT_URL}&recv_buf_size=16777216" lcm-logger --quiet \
  --channel 'ATLAS_POSE|ATLAS_HEALTH|ATLAS_RAW_LASER' "$WORK/session.lcm" >"$WORK/logger.err" 2>&1 &
LOGGER_PID=$!
PIDS+=("$LOGGER_PID")
start_atlasd "$WORK/atlasd.toml" --health-every 10
for _ in $(seq 100); do grep -q "^atlasd: up" "$WORK/atlasd.err" 2>/dev/null && break; sleep 0.1; done
sleep 0.5
t0=$(date +%s.%N)
lcm-logplayer --speed "$SPEED" "$WORK/play.lcm" >"$WORK/player.out" 2>"$WORK/player.err" ||
  fail "lcm-logplayer failed: $(cat "$WORK/player.err")"
t1=$(date +%s.%N)
sleep 2  # the loop steps what is pending, and publishes its health
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero"
sleep 0.3
stop_logger
"$ATLASD" --config "$WORK/atlasd.toml" --export-atlas "$WORK/live" 2>"$WORK/export.err" ||
  fail "export: $(cat "$WORK/export.err")"
"$LOG_SUMMARY" "$WORK/session.lcm" --poses "$WORK/live_poses.txt" --scans "$WORK/live_scans.txt" \
  >"$WORK/summary.txt" || fail "atlas-lcm-log-summary failed"

# live poses "t x y theta frame q r" -> trajectory.tsv "stamp frame x y theta" on the stamps of
# the scans received ("r t").
awk -v S="$SPEED" -v out="$WORK/live/trajectory.tsv" -v stats="$WORK/mapping.txt" '
  BEGIN { last = -1 }
  NR == FNR { R[n] = $1; T[n] = $2; n++; next }
  {
    r = $7
    while (j < n && R[j] <= r + 0.005) j++
    k = last + 1  # the next scan, if the logger had it before this pose
    if (k >= j || (r - R[k]) * S > 0.25) k = j - 1  # else the last one received (scans lost)
    if (k <= last || (r - R[k]) * S > 0.25) { far++; next }
    last = k; kept++; d = (r - R[k]) * S; sum += d; if (d > dmax) dmax = d
    printf "%.6f\t%s\t%s\t%s\t%s\n", T[k], $5, $2, $3, $4 > out
  }
  END { printf "kept=%d far=%d mean_delay_log_s=%.6f max_delay_log_s=%.6f\n", kept, far,
        kept ? sum / kept : 0, dmax > stats }' "$WORK/live_scans.txt" "$WORK/live_poses.txt"
sed -i '1i # atlasd poses from the LCM input on log scan stamps: timestamp frame x y theta' "$WORK/live/trajectory.tsv"
cat "$WORK/mapping.txt"
S_=$WORK/summary.txt
received=$(summary_value "$S_" events.ATLAS_RAW_LASER)
steps=$(summary_value "$S_" health.last_steps)
dropped=$(summary_value "$S_" health.dropped_scans)
laser_msgs=$(summary_value "$S_" health.laser.messages)
laser_drops=$(summary_value "$S_" health.laser.queue_drops)
odo_drops=$(summary_value "$S_" health.odometry.queue_drops)
bad=$(( $(summary_value "$S_" health.laser.bad_messages) + $(summary_value "$S_" health.odometry.bad_messages) ))
replay_steps=$(grep -vc '^#' "$WORK/replay/timing.tsv")
echo "scans: $scans played, $received recorded by the logger, $laser_msgs taken by atlasd, $steps stepped (replay $replay_steps); dropped: loop $dropped, laser queue $laser_drops, odometry queue $odo_drops; bad $bad; played in $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s"
[ "$dropped" = 0 ] && [ "$laser_drops" = 0 ] && [ "$odo_drops" = 0 ] ||
  fail "scans or odometry dropped: loop $dropped, laser queue $laser_drops, odometry queue $odo_drops"
[ "$bad" = 0 ] || fail "$bad messages atlasd could not decode"
[ "$laser_msgs" = "$scans" ] || fail "atlasd took $laser_msgs of the $scans scans played"
[ "$steps" = "$scans" ] || fail "atlasd stepped $steps of the $scans scans played"
[ "$replay_steps" = "$scans" ] || fail "atlas-replay stepped $replay_steps of the $scans scans"
compare_with_replay "LCM input ($TYPES)"
