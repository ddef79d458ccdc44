#!/usr/bin/env bash
# HIL (e): a bad configuration makes atlasd exit 78 (EX_CONFIG) naming the key and its line,
# both when started and with --check-config; a good one passes --check-config.
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
pass "a missing configuration file: exit 78"
