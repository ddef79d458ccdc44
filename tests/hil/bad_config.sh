#!/usr/bin/env bash
# HIL (e): a bad configuration makes atlasd exit 78 (EX_CONFIG) naming the key and its line,
# both when started and with --check-config; a good one passes --check-config; a missing file
# and a directory are refused with the reason; a SIGHUP reload refuses what --check-config does.
source "$(dirname "$0")/hil_lib.sh"
cat >"$WORK/bad.toml" <<'TOML'
[laser]
device = "/dev/null"
baud = 1234
[loop]
step_budget_ms = 10.0
no_such_key = 1
TOML
expect_exit 78 'bad.toml:3:.*laser.baud' "$ATLASD" --config "$WORK/bad.toml"
grep -q 'bad.toml:6:.*loop.no_such_key' "$WORK/err" || fail "no error naming loop.no_such_key on line 6"
pass "atlasd --config bad.toml: exit 78, laser.baud (line 3) and loop.no_such_key (line 6) named"
expect_exit 78 'laser.baud' "$ATLASD" --check-config "$WORK/bad.toml"
write_config "$WORK/good.toml" 1
expect_exit 0 'configuration is valid' "$ATLASD" --check-config "$WORK/good.toml"
pass "--check-config: 78 on the bad file, 0 on a good one"
expect_exit 78 'absent.toml: cannot open the configuration file: No such file or directory' \
  "$ATLASD" --config "$WORK/absent.toml"
pass "a missing configuration file: exit 78, with the reason"
expect_exit 78 'is a directory, not a configuration file' "$ATLASD" --config "$WORK"
pass "a directory as the configuration file: exit 78, said so"
# SIGHUP with a file that --check-config refuses: the reload is refused with the same messages
# (file, line and key) and atlasd keeps running. No devices: atlasd reports them and runs on.
cat >"$WORK/reload.toml" <<TOML
[laser]
device = "$WORK/dev/laser"
[odometry]
interface = "unix:$WORK/dev/can"
[lcm]
url = "memq://"
[state]
directory = "$WORK/state"
[scheduling]
policy = "other"
priority = 0
TOML
start_atlasd "$WORK/reload.toml"
sleep 1
kill -0 "$ATLASD_PID" || fail "atlasd with reload.toml died"
printf '[atlas]\nmax_hypotheses = 1\n' >>"$WORK/reload.toml"
rc=0
"$ATLASD" --check-config "$WORK/reload.toml" >/dev/null 2>"$WORK/reload-check.err" || rc=$?
[ "$rc" = 78 ] || fail "--check-config with atlas.max_hypotheses = 1 exited $rc, want 78"
kill -HUP "$ATLASD_PID"
sleep 1
kill -0 "$ATLASD_PID" || fail "atlasd died at the SIGHUP"
grep -q 'reload refused' "$WORK/atlasd.err" || fail "the SIGHUP reload was not refused"
grep -qF "$(cat "$WORK/reload-check.err" | head -n 1)" "$WORK/atlasd.err" ||
  fail "the reload did not refuse with --check-config's message: $(head -n 1 "$WORK/reload-check.err")"
grep -q 'reload.toml:13:18: atlas.max_hypotheses' "$WORK/atlasd.err" ||
  fail "the refused reload did not name atlas.max_hypotheses on line 13"
stop_pid "$ATLASD_PID" 2.0 || fail "atlasd exited non-zero after the refused reload"
pass "SIGHUP with atlas.max_hypotheses = 1: refused as --check-config refuses it, atlasd runs on"
