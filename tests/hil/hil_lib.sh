# Shared by the hardware-in-loop scripts (sourced). Needs ATLASD, FAKEDEV, LOG_SUMMARY and
# DATASET in the environment (tests/hil/CMakeLists.txt sets them). Every process started here
# is stopped by its own pid on exit.
set -euo pipefail
WORK=$(mktemp -d /tmp/atlasd-hil.XXXXXX)
PIDS=()
cleanup() {
  local p
  for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null || true; done
  sleep 0.2
  for p in "${PIDS[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  if [ "${HIL_KEEP:-0}" = 1 ]; then echo "kept $WORK" >&2; else rm -rf "$WORK"; fi
}
trap cleanup EXIT

fail() { echo "FAIL: $*" >&2; for f in "$WORK"/*.err; do [ -f "$f" ] && { echo "--- $f" >&2; tail -n 15 "$f" >&2; }; done; exit 1; }
pass() { echo "PASS: $*"; }

# expect_exit RC PATTERN CMD...: CMD exits RC, and PATTERN (grep -E) is in what it wrote to
# stderr or stdout, which stay in $WORK/err and $WORK/out for further checks.
expect_exit() {
  local want=$1 pattern=$2 rc=0
  shift 2
  "$@" >"$WORK/out" 2>"$WORK/err" || rc=$?
  if [ "$rc" != "$want" ]; then
    fail "$* -> exit $rc, want $want: $(head -c 400 "$WORK/err")"
  elif ! grep -qE -- "$pattern" "$WORK/err" "$WORK/out"; then
    fail "$* -> no '$pattern' in: $(head -c 400 "$WORK/err") $(head -c 200 "$WORK/out")"
  fi
}

need_multicast() {
  if [ -z "${LCM_DEFAULT_URL:-}" ] || ! ip route show 224.0.0.0/4 2>/dev/null | grep -q dev; then
    echo "SKIP: needs a private network namespace with a multicast route (scripts/test.sh)" >&2
    exit 77
  fi
}
need_dataset() {
  [ -f "$DATASET" ] || { echo "SKIP: dataset $DATASET absent" >&2; exit 77; }
}

# write_config FILE SPEED [extra TOML lines...]: atlasd on the fakes in $WORK/dev.
write_config() {
  local file=$1 speed=$2
  shift 2
  cat >"$file" <<TOML
# hardware-in-loop configuration (written by tests/hil/hil_lib.sh)
[laser]
device = "$WORK/dev/laser"
unit = "cm"
max_range_m = 50.0
[odometry]
interface = "unix:$WORK/dev/can"
# at SPEED times real time the wheels seem to turn SPEED times faster
max_speed_mps = $(awk -v s="$speed" 'BEGIN { print 3 * s }')
slack_m = $(awk -v s="$speed" 'BEGIN { print 0.02 * s }')
[sonar]
enabled = true
device = "$WORK/dev/sonar"
[lcm]
url = "${LCM_DEFAULT_URL:-udpm://239.255.76.67:7667?ttl=0}"
republish_raw = true
health_period_s = 0.5
[state]
directory = "$WORK/state"
save_period_s = ${SAVE_PERIOD_S:-2.0}
TOML
  local line
  for line in "$@"; do echo "$line" >>"$file"; done
}

# start_fakedev ARGS...: plays $DATASET into $WORK/dev; waits for the devices to exist.
start_fakedev() {
  "$FAKEDEV" --log "$DATASET" --dir "$WORK/dev" --wait-for-drivers --progress-every 0 "$@" \
    >"$WORK/fakedev.out" 2>"$WORK/fakedev.err" &
  FAKEDEV_PID=$!
  PIDS+=("$FAKEDEV_PID")
  local i
  for i in $(seq 100); do
    [ -e "$WORK/dev/laser" ] && [ -e "$WORK/dev/can" ] && [ -e "$WORK/dev/sonar" ] && return 0
    kill -0 "$FAKEDEV_PID" 2>/dev/null || fail "atlas-fakedev exited at start"
    sleep 0.05
  done
  fail "atlas-fakedev made no devices in 5 s"
}

start_logger() {
  # A large receive buffer: at a few times real time the raw channels come in bursts.
  LCM_DEFAULT_URL="${LCM_DEFAULT_URL}&recv_buf_size=16777216" lcm-logger --quiet "$WORK/session.lcm" >"$WORK/logger.err" 2>&1 &
  LOGGER_PID=$!
  PIDS+=("$LOGGER_PID")
  sleep 0.3
}

# stop_logger: lcm-logger ends its file at an event (SIGINT), so that atlas-lcm-log-summary and
# atlasd --replay, which refuse a truncated log, read a whole one.
stop_logger() {
  kill -INT "$LOGGER_PID"
  wait "$LOGGER_PID" || true
}

# start_notify_listener: a fake systemd notify socket at $WORK/notify.sock (give it to atlasd
# as NOTIFY_SOCKET); each notification goes to $WORK/notify.log as "SECONDS LINE".
start_notify_listener() {
  python3 - "$WORK/notify.sock" "$WORK/notify.log" <<'PY' &
import socket, sys, time
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
s.bind(sys.argv[1])
t0 = time.monotonic()
with open(sys.argv[2], "w", buffering=1) as f:
    while True:
        data = s.recv(4096).decode(errors="replace")
        for line in data.split("\n"):
            if line:
                f.write("%.3f %s\n" % (time.monotonic() - t0, line))
PY
  PIDS+=($!)
  local i
  for i in $(seq 50); do [ -S "$WORK/notify.sock" ] && return 0; sleep 0.1; done
  fail "the fake notify socket did not appear"
}

# start_atlasd CONFIG [args...]
start_atlasd() {
  local config=$1
  shift
  "$ATLASD" --config "$config" "$@" >"$WORK/atlasd.out" 2>"$WORK/atlasd.err" &
  ATLASD_PID=$!
  PIDS+=("$ATLASD_PID")
}

# stop_pid PID SECONDS: SIGTERM, and the time it took to exit must be under SECONDS.
stop_pid() {
  local pid=$1 limit=$2 t0 t1
  t0=$(date +%s.%N)
  kill -TERM "$pid"
  local rc=0
  wait "$pid" || rc=$?
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" -v l="$limit" 'BEGIN { exit !(b - a < l) }' ||
    fail "pid $pid took $(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') s to stop (limit $limit s)"
  return "$rc"
}

# cpu_seconds SECONDS PID...: sleeps SECONDS, then prints the wall time it slept and, for each
# PID, the CPU time (utime + stime, /proc/PID/stat) it used meanwhile, in seconds, on one line.
cpu_seconds() {
  local seconds=$1 p t0 t1
  shift
  local before=() after=()
  for p in "$@"; do before+=("$(awk '{ print $14 + $15 }' "/proc/$p/stat")"); done
  t0=$(date +%s.%N)
  sleep "$seconds"
  for p in "$@"; do after+=("$(awk '{ print $14 + $15 }' "/proc/$p/stat")"); done
  t1=$(date +%s.%N)
  awk -v t0="$t0" -v t1="$t1" -v hz="$(getconf CLK_TCK)" -v b="${before[*]}" -v a="${after[*]}" \
    'BEGIN { n = split(b, B, " "); split(a, A, " "); line = sprintf("%.3f", t1 - t0)
             for (i = 1; i <= n; ++i) line = line sprintf(" %.3f", (A[i] - B[i]) / hz); print line }'
}

summary_value() {  # summary_value FILE KEY
  grep -E "^$2=" "$1" | head -n 1 | cut -d= -f2
}

# compare_with_replay LABEL: the live run ($WORK/live, its trajectory.tsv on the log's scan
# stamps, and $WORK/mapping.txt "kept=K far=F ..." from that mapping) against atlas-replay's
# ($WORK/replay) on the benchmark's relations ($RELATIONS). Fails unless the live run has a pose
# for at least 99 % of the scans replay stepped, at most 1 % of its poses were left out by the
# mapping, the matched relation counts agree within 2 % and the mean translational / rotational
# relation errors within 0.5 m / 3 deg; prints the line of both scores (LABEL names the live run).
compare_with_replay() {
  local label=$1 replay_steps kept far rt rr rm_ lt lr lm line
  replay_steps=$(grep -vc '^#' "$WORK/replay/timing.tsv")
  kept=$(sed -E 's/kept=([0-9]+).*/\1/' "$WORK/mapping.txt")
  far=$(sed -E 's/.*far=([0-9]+).*/\1/' "$WORK/mapping.txt")
  "$ATLAS_EVAL" --relations "$RELATIONS" --atlas "$WORK/replay" --json >"$WORK/score_replay.json" ||
    fail "scoring replay failed"
  "$ATLAS_EVAL" --relations "$RELATIONS" --atlas "$WORK/live" --json >"$WORK/score_live.json" ||
    fail "scoring $label failed"
  field() {  # field FILE KEY SUBKEY: a number from atlas-eval's JSON
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); v=d[sys.argv[2]]; print(v[sys.argv[3]] if len(sys.argv) > 3 else v)' "$@"
  }
  rt=$(field "$WORK/score_replay.json" translation_m mean)
  rr=$(field "$WORK/score_replay.json" rotation_deg mean)
  rm_=$(field "$WORK/score_replay.json" matched)
  lt=$(field "$WORK/score_live.json" translation_m mean)
  lr=$(field "$WORK/score_live.json" rotation_deg mean)
  lm=$(field "$WORK/score_live.json" matched)
  line="replay: $replay_steps steps, $rm_ relations, trans ${rt} m, rot ${rr} deg, $(field "$WORK/score_replay.json" frames) frames; $label: $kept poses on scan stamps ($far left out), $lm relations, trans ${lt} m, rot ${lr} deg, $(field "$WORK/score_live.json" frames) frames"
  echo "$line"
  awk -v k="$kept" -v n="$replay_steps" 'BEGIN { exit !(k >= 0.99 * n) }' ||
    fail "$label stepped $kept of the $replay_steps scans replay stepped"
  awk -v f="$far" -v k="$kept" 'BEGIN { exit !(f <= 0.01 * (k + f)) }' || fail "$far poses far from every scan"
  awk -v a="$rm_" -v b="$lm" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 0.02 * a) }' ||
    fail "matched relations differ: $line"
  awk -v a="$rt" -v b="$lt" -v c="$rr" -v e="$lr" \
    'BEGIN { d = a - b; if (d < 0) d = -d; g = c - e; if (g < 0) g = -g; exit !(d <= 0.5 && g <= 3.0) }' ||
    fail "$label and replay scores differ: $line"
  pass "$line"
}
