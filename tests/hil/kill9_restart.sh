#!/usr/bin/env bash
# HIL (d): kill -9 and restart. atlasd maps mit-csail played by atlas-fakedev at 2x with
# checkpoints every 1 s, is killed with SIGKILL mid-run, and then:
#  - the store is intact: PRAGMA integrity_check says ok, it holds the atlas image, frame rows
#    and edge rows, and the saved atlas is at most a few seconds behind the steps made before
#    the kill (checkpoint period 1 s + health period 0.5 s, 4 s allowed);
#  - a restarted atlasd (same state directory, devices still playing) loads it: the log says it
#    resumed the saved atlas with that many frames and steps, and its first health line already
#    counts those frames and the robot's new one; it maps on and saves again; a SIGHUP with a changed
#    atlas parameter is applied to it; SIGTERM stops it with exit 0.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
DB=$WORK/state/atlas.sqlite
SAVE_PERIOD_S=1.0 write_config "$WORK/atlasd.toml" 2
"$ATLASD" --check-config "$WORK/atlasd.toml" >/dev/null || fail "test config rejected: $("$ATLASD" --check-config "$WORK/atlasd.toml" 2>&1)"
start_fakedev --speed 2
start_atlasd "$WORK/atlasd.toml" --health-every 0.5
sleep 14
kill -0 "$ATLASD_PID" || fail "atlasd died"
kill -9 "$ATLASD_PID"
wait "$ATLASD_PID" 2>/dev/null || true
steps_before=$(grep -oE 'steps [0-9]+' "$WORK/atlasd.err" | tail -n 1 | cut -d' ' -f2)
mv "$WORK/atlasd.err" "$WORK/atlasd-1.err"
[ -f "$DB" ] || fail "no store at $DB"

q() { sqlite3 -readonly "$DB" "$1"; }
integrity=$(q 'PRAGMA integrity_check')
[ "$integrity" = ok ] || fail "integrity_check after kill -9: $integrity"
frames=$(q 'SELECT count(*) FROM frames')
edges=$(q 'SELECT count(*) FROM edges')
image=$(q "SELECT length(value) FROM metadata WHERE key = 'atlas_image'")
saved_steps=$(q "SELECT CAST(value AS TEXT) FROM metadata WHERE key = 'atlas_steps'")
batches=$(q "SELECT CAST(value AS TEXT) FROM metadata WHERE key = 'batch_sequence'")
echo "after kill -9: integrity=$integrity frames=$frames edges=$edges image_bytes=${image:-0}" \
  "saved_steps=${saved_steps:-0} batches=${batches:-0} steps_at_last_health_line=${steps_before:-0}"
[ "${frames:-0}" -ge 1 ] || fail "no frame row saved"
[ "${image:-0}" -gt 0 ] || fail "no atlas image saved"
# At 2x, scans come at ~10 Hz: 4 s is 40 steps.
[ "$((steps_before - saved_steps))" -le 40 ] ||
  fail "the store is $((steps_before - saved_steps)) steps behind (saved $saved_steps, made $steps_before)"

start_atlasd "$WORK/atlasd.toml" --health-every 0.5
sleep 4
# SIGHUP with a changed atlas parameter: applied to the running (resumed) atlas.
printf '[atlas]\nmatch_candidates_per_step = 3\n' >>"$WORK/atlasd.toml"
kill -HUP "$ATLASD_PID"
sleep 2
kill -0 "$ATLASD_PID" || fail "restarted atlasd died"
grep -q 'reload: applied: atlas.match_candidates_per_step' "$WORK/atlasd.err" ||
  fail "SIGHUP did not apply atlas.match_candidates_per_step: $(grep reload "$WORK/atlasd.err")"
stop_pid "$ATLASD_PID" 1.0 || fail "restarted atlasd exited non-zero"
resumed=$(grep -m1 'resumed the saved atlas' "$WORK/atlasd.err" || true)
[ -n "$resumed" ] || fail "the restart did not resume the saved atlas"
echo "restart: $resumed"
grep -q "resumed the saved atlas from $DB: $frames frames, .* $saved_steps steps" <<<"$resumed" ||
  fail "resumed something else than the saved $frames frames / $saved_steps steps"
first_frames=$(grep -m1 -oE 'frames [0-9]+' "$WORK/atlasd.err" | cut -d' ' -f2)
echo "restart: first health line counts ${first_frames:-0} frames"
# The saved frames and the robot's new one.
[ "${first_frames:-0}" -ge "$((frames + 1))" ] ||
  fail "first health line counts ${first_frames:-0} frames, saved $frames (+1 new)"
grep -q 'saved [1-9][0-9]* checkpoints' "$WORK/atlasd.err" || fail "the restarted atlasd saved nothing"
[ "$(q 'PRAGMA integrity_check')" = ok ] || fail "integrity_check after the restart"
steps_after=$(q "SELECT CAST(value AS TEXT) FROM metadata WHERE key = 'atlas_steps'")
[ "$steps_after" -gt "$saved_steps" ] || fail "no step saved after the restart ($steps_after)"
pass "kill -9: store intact ($frames frames, $edges edges, ${image} bytes image, $((steps_before - saved_steps)) steps behind); restart resumed it and saved on to step $steps_after"
