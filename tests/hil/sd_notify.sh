#!/usr/bin/env bash
# HIL (f): under a fake NOTIFY_SOCKET with a watchdog, atlasd sends READY=1 once the devices
# run, then WATCHDOG=1 and STATUS=; WATCHDOG=1 stops while the loop is stalled on purpose
# (SIGUSR1 with --debug-stall-on-usr1) and resumes after; SIGTERM gives STOPPING=1 last and
# atlasd exits 0 within a second.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
write_config "$WORK/atlasd.toml" 2
start_notify_listener
start_fakedev --speed 2
NOTIFY_SOCKET="$WORK/notify.sock" WATCHDOG_USEC=1000000 \
  bash -c 'export WATCHDOG_PID=$$; exec "$@"' atlasd "$ATLASD" --config "$WORK/atlasd.toml" \
  --debug-stall-on-usr1 >"$WORK/atlasd.out" 2>"$WORK/atlasd.err" &
ATLASD_PID=$!
PIDS+=("$ATLASD_PID")
for i in $(seq 100); do grep -q 'READY=1' "$WORK/notify.log" 2>/dev/null && break; sleep 0.1; done
grep -q 'READY=1' "$WORK/notify.log" || fail "no READY=1 within 10 s"
sleep 3
kill -0 "$ATLASD_PID" || fail "atlasd died"
pings_before=$(grep -c 'WATCHDOG=1' "$WORK/notify.log" || true)
[ "$pings_before" -ge 3 ] || fail "only $pings_before WATCHDOG=1 in 3 s (want >= 3 at 0.5 s)"
grep -q 'STATUS=' "$WORK/notify.log" || fail "no STATUS="
pass "READY=1, then $pings_before watchdog pings in 3 s, STATUS sent"
# Stall the loop for 5 s: no ping from 1 s into the stall until it ends.
kill -USR1 "$ATLASD_PID"
sleep 1
n1=$(grep -c 'WATCHDOG=1' "$WORK/notify.log" || true)
sleep 3
n2=$(grep -c 'WATCHDOG=1' "$WORK/notify.log" || true)
[ "$n2" = "$n1" ] || fail "$((n2 - n1)) WATCHDOG=1 while the loop was stalled"
grep -q 'STATUS=loop stalled' "$WORK/notify.log" || fail "no STATUS about the stall"
pass "no WATCHDOG=1 during 3 s of a stalled loop; STATUS says so"
sleep 3
n3=$(grep -c 'WATCHDOG=1' "$WORK/notify.log" || true)
[ "$n3" -gt "$n2" ] || fail "WATCHDOG=1 did not resume after the stall"
pass "watchdog pings resumed after the stall"
stop_pid "$ATLASD_PID" 1.0 || fail "atlasd exited non-zero on SIGTERM"
sleep 0.2
last=$(tail -n 1 "$WORK/notify.log" | cut -d' ' -f2-)
[ "$last" = "STOPPING=1" ] || fail "last notification is '$last', want STOPPING=1"
# Order: READY before the first WATCHDOG, STOPPING last.
first_ready=$(grep -n 'READY=1' "$WORK/notify.log" | head -n1 | cut -d: -f1)
first_ping=$(grep -n 'WATCHDOG=1' "$WORK/notify.log" | head -n1 | cut -d: -f1)
[ "$first_ready" -lt "$first_ping" ] || fail "WATCHDOG=1 before READY=1"
pass "SIGTERM: STOPPING=1 last, exit 0 within 1 s; order READY < WATCHDOG < STOPPING"
