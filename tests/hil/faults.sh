#!/usr/bin/env bash
# HIL (c): garbage bytes, CRC errors and an odometry counter jump are counted by the drivers,
# published in health, and survived (atlasd keeps stepping and exits cleanly).
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
write_config "$WORK/atlasd.toml" 2
start_logger
start_fakedev --speed 2 --garbage-every 20 --corrupt-every 30 --jump-every 300
start_atlasd "$WORK/atlasd.toml"
sleep 12
kill -0 "$ATLASD_PID" || fail "atlasd died"
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero"
sleep 0.3
stop_logger
"$LOG_SUMMARY" "$WORK/session.lcm" >"$WORK/summary.txt"
cat "$WORK/summary.txt"
S="$WORK/summary.txt"
for k in laser.garbage_bytes laser.bad_crc sonar.garbage_bytes sonar.bad_crc odometry.discontinuities; do
  v=$(summary_value "$S" "health.$k")
  [ -n "$v" ] && [ "$v" -gt 0 ] || fail "health.$k = '$v', want > 0"
done
steps=$(summary_value "$S" health.last_steps)
[ "$steps" -gt 50 ] || fail "only $steps steps"
gap=$(summary_value "$S" pose.max_gap_s)
awk -v g="$gap" 'BEGIN { exit !(g < 0.5) }' || fail "ATLAS_POSE stopped for $gap s"
pass "garbage, CRC errors and odometry jumps counted in health; $steps steps, max pose gap $gap s"
# Each driver's state changes on stderr (DriverLog).
for d in laser odometry sonar; do
  grep -qE "^atlasd: $d .*: running" "$WORK/atlasd.err" || fail "no '$d ...: running' on stderr"
done
pass "each driver said on stderr when it ran"
# The version, at start-up and in the health message, is --version's.
version=$("$ATLASD" --version)
version=${version#atlasd }
grep -qxF "atlasd: version $version" "$WORK/atlasd.err" || fail "no 'atlasd: version $version' on stderr"
[ "$(summary_value "$S" health.version)" = "$version" ] ||
  fail "health.version '$(summary_value "$S" health.version)', --version says '$version'"
pass "version $version at start-up and in health"
