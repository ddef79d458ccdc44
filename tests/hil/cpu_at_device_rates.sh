#!/usr/bin/env bash
# CPU use of atlasd at the real device rates (the target: at most 5 % of one core over
# several minutes). Not a ctest (it runs for minutes): run by hand inside a private network
# namespace (docs/atlasd.md), with ATLASD, FAKEDEV and SIM set:
#
#   SECONDS_MEASURED=180 ATLASD=... FAKEDEV=... SIM=.../atlas-sim POSE_LATENCY=.../atlas-pose-latency \
#     bash tests/hil/cpu_at_device_rates.sh
#
# atlas-sim makes a 0.16 km run through a generated building with the laser at 75 Hz (181
# beams), odometry at 50 Hz and the P3-DX sonar ring at 10 Hz; atlas-fakedev plays it at real
# time on the fake devices; atlasd maps it with the shipped defaults (raw republishing off).
# After a 15 s warm-up, utime + stime of the atlasd process (/proc/PID/stat) are read over
# SECONDS_MEASURED seconds of wall time; the figure is their sum over the wall time, in % of
# one core. Also printed: the atlas-fakedev process's own use (it shares the machine), the
# last health line, and (atlas-pose-latency, over the same seconds) the latency from the laser
# driver's arrival stamp of each scan to its ATLAS_POSE received by an LCM subscriber.
# The shipped defaults run the loop and driver threads SCHED_FIFO 40 (where allowed). RT_PRIORITY=N
# (optional) sets [scheduling] policy "fifo" at priority N with mlockall (systemd/atlasd.service
# allows LimitRTPRIO=50) and runs the subscriber under `chrt -f N`, as a robot's consumer of the
# pose would run.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
: "${SIM:?set SIM to the atlas-sim binary}"
MEASURED=${SECONDS_MEASURED:-180}
"$SIM" --rooms 24 --length-km 0.16 --seed 3 --laser-hz 75 --odometry-hz 50 --sonar p3dx \
  --sonar-hz 10 --out "$WORK/sim" --quiet
DATASET=$WORK/sim/run.clf
write_config "$WORK/atlasd.toml" 1
# write_config's laser section is for the recorded logs; the simulated laser reaches 30 m.
sed -i 's/^max_range_m = 50.0/max_range_m = 30.0\nangular_resolution_deg = 1.0/; /^republish_raw = true/d; /^health_period_s = 0.5/d' "$WORK/atlasd.toml"
if [ -n "${RT_PRIORITY:-}" ]; then
  # write_config writes no [scheduling] section.
  printf '\n[scheduling]\npolicy = "fifo"\npriority = %d\nmlockall = true\n' "$RT_PRIORITY" \
    >>"$WORK/atlasd.toml"
  POSE_LATENCY_CMD=(chrt -f "$RT_PRIORITY" "$POSE_LATENCY")
else
  POSE_LATENCY_CMD=("$POSE_LATENCY")
fi
start_fakedev --speed 1
start_atlasd "$WORK/atlasd.toml" --health-every 30
sleep 15
kill -0 "$ATLASD_PID" || fail "atlasd died"
"${POSE_LATENCY_CMD[@]}" --seconds "$MEASURED" >"$WORK/latency.txt" 2>&1 &
LATENCY_PID=$!
PIDS+=("$LATENCY_PID")
read -r wall a f < <(cpu_seconds "$MEASURED" "$ATLASD_PID" "$FAKEDEV_PID")
wait "$LATENCY_PID" || true
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero"
echo "scan arrival -> ATLAS_POSE received: $(cat "$WORK/latency.txt")"
grep -E '^atlasd: up' "$WORK/atlasd.err" | tail -n 1
awk -v a="$a" -v f="$f" -v w="$wall" 'BEGIN {
  printf "atlasd cpu: %.2f %% of one core over %.0f s (%.2f s of utime+stime); atlas-fakedev: %.2f %%\n",
         100 * a / w, w, a, 100 * f / w }' | tee "$WORK/cpu.txt"
awk '{ exit !($3 + 0 <= 5.0) }' "$WORK/cpu.txt" || fail "above 5 %: $(cat "$WORK/cpu.txt")"
pass "$(cat "$WORK/cpu.txt")"
