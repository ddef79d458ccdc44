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
rc=0
"$ATLASD" --config "$WORK/bad.toml" >"$WORK/run.out" 2>"$WORK/run.err" || rc=$?
[ "$rc" = 78 ] || fail "atlasd with a bad config exited $rc, want 78"
grep -q 'bad.toml:3:.*laser.baud' "$WORK/run.err" || fail "no error naming laser.baud on line 3"
grep -q 'bad.toml:6:.*loop.no_such_key' "$WORK/run.err" || fail "no error naming loop.no_such_key on line 6"
pass "atlasd --config bad.toml: exit 78, laser.baud (line 3) and loop.no_such_key (line 6) named"
rc=0
"$ATLASD" --check-config "$WORK/bad.toml" >"$WORK/check.out" 2>"$WORK/check.err" || rc=$?
[ "$rc" = 78 ] || fail "--check-config exited $rc, want 78"
grep -q 'laser.baud' "$WORK/check.err" || fail "--check-config did not name laser.baud"
write_config "$WORK/good.toml" 1
"$ATLASD" --check-config "$WORK/good.toml" >"$WORK/good.out" 2>&1 || fail "a good config was refused"
pass "--check-config: 78 on the bad file, 0 on a good one"
rc=0
"$ATLASD" --config "$WORK/absent.toml" >/dev/null 2>"$WORK/absent.err" || rc=$?
[ "$rc" = 78 ] || fail "a missing config file exited $rc, want 78"
grep -q 'absent.toml: cannot open the configuration file: No such file or directory' "$WORK/absent.err" ||
  fail "the missing file's message has no reason: $(cat "$WORK/absent.err")"
pass "a missing configuration file: exit 78, with the reason"
rc=0
"$ATLASD" --config "$WORK" >/dev/null 2>"$WORK/dir.err" || rc=$?
[ "$rc" = 78 ] || fail "a directory as the config file exited $rc, want 78"
grep -q 'is a directory, not a configuration file' "$WORK/dir.err" ||
  fail "a directory as the config file: $(cat "$WORK/dir.err")"
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
