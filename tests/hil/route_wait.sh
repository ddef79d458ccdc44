#!/usr/bin/env bash
# HIL: a robot that boots before its network. atlasd started without a route to the LCM
# multicast group waits (does not exit; says why on stderr once, and STATUS= to systemd,
# no READY=1), and once the route appears it opens LCM, reaches READY=1 and publishes poses.
# Runs in a network namespace of its own (unshare -n: only lo, no route until the test adds
# one), so it never touches the namespace it was started in.
if [ -z "${ROUTE_WAIT_INNER:-}" ]; then
  if ! unshare -n true 2>/dev/null; then
    echo "SKIP: needs unshare -n (root or user namespaces)" >&2
    exit 77
  fi
  exec unshare -n env ROUTE_WAIT_INNER=1 bash "$0" "$@"
fi
source "$(dirname "$0")/hil_lib.sh"
need_dataset
ip link set lo up
ip link set lo multicast on
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
! ip route show 224.0.0.0/4 | grep -q . || fail "a fresh namespace has a multicast route"
write_config "$WORK/atlasd.toml" 2
start_notify_listener
start_fakedev --speed 2
NOTIFY_SOCKET="$WORK/notify.sock" "$ATLASD" --config "$WORK/atlasd.toml" \
  >"$WORK/atlasd.out" 2>"$WORK/atlasd.err" &
ATLASD_PID=$!
PIDS+=("$ATLASD_PID")
sleep 2.5
kill -0 "$ATLASD_PID" 2>/dev/null || fail "atlasd exited without a multicast route"
[ "$(grep -c "no route to lcm.url's multicast group" "$WORK/atlasd.err")" = 1 ] ||
  fail "want the missing route said once on stderr"
grep -q 'STATUS=waiting for a multicast route' "$WORK/notify.log" || fail "no STATUS= while waiting"
! grep -q 'READY=1' "$WORK/notify.log" || fail "READY=1 before there is a route"
pass "no route: atlasd waits, says why once, STATUS= and no READY=1"

ip route add 224.0.0.0/4 dev lo
start_logger
for i in $(seq 100); do grep -q 'READY=1' "$WORK/notify.log" 2>/dev/null && break; sleep 0.1; done
grep -q 'READY=1' "$WORK/notify.log" || fail "no READY=1 within 10 s of the route"
sleep 3
kill -0 "$ATLASD_PID" 2>/dev/null || fail "atlasd died"
stop_pid "$ATLASD_PID" 1.5 || fail "atlasd exited non-zero on SIGTERM"
sleep 0.3
stop_logger
"$LOG_SUMMARY" "$WORK/session.lcm" >"$WORK/summary.txt"
poses=$(summary_value "$WORK/summary.txt" pose.count)
[ -n "$poses" ] && [ "$poses" -gt 10 ] || fail "only '$poses' ATLAS_POSE after the route came"
pass "route added: READY=1 and $poses poses published"
