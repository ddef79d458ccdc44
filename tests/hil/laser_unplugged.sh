#!/usr/bin/env bash
# HIL (b): the laser unplugged for 10 s mid-run (atlas-fakedev closes its pty and recreates it).
# atlasd keeps publishing the pose on odometry alone (no gap in ATLAS_POSE longer than 1 s),
# reports the fault in health (status "LASER FAULT", the laser driver reconnecting), and
# recovers: the laser driver runs again and scans are stepped after the drop. The gap limit is
# 1 s: dead reckoning starts 0.5 s (data time) after the last scan, and scans of the recorded
# log come at about 5 Hz.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
write_config "$WORK/atlasd.toml" 1
start_logger
start_fakedev --speed 1 --fault-device laser --drop-after 5 --drop-for 10
start_atlasd "$WORK/atlasd.toml" --health-every 1
sleep 21
kill -0 "$ATLASD_PID" || fail "atlasd died"
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero"
sleep 0.3
stop_logger
"$LOG_SUMMARY" "$WORK/session.lcm" >"$WORK/summary.txt"
cat "$WORK/summary.txt"
S="$WORK/summary.txt"
gap=$(summary_value "$S" pose.max_gap_s)
awk -v g="$gap" 'BEGIN { exit !(g < 1.0) }' || fail "ATLAS_POSE stopped for $gap s"
[ "$(summary_value "$S" health.laser_fault_seen)" = 1 ] || fail "health never reported the laser fault"
states=$(summary_value "$S" health.laser.states)
case "$states" in *running*,*reconnecting*,*running*|*running*,*stalled*,*running*) ;; *) fail "laser states seen: $states" ;; esac
[ "$(summary_value "$S" health.laser.reconnects)" -ge 1 ] || fail "no laser reconnect counted"
grep -q 'LASER FAULT' "$WORK/atlasd.err" || fail "the health line never showed the fault"
tail -n 3 "$WORK/atlasd.err" | grep -q 'LASER FAULT' && fail "the fault is still reported at the end"
pass "poses without a gap > 1 s (max $gap s), fault reported, laser states $states, recovered"
