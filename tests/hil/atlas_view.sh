#!/usr/bin/env bash
# HIL: atlas-view in a real browser. atlasd maps mit-csail played by atlas-fakedev at 4x real
# time; atlas-view serves its page on this namespace's loopback; headless Chromium opens it and
# tests/hil/browser_check.py reads the DOM over the DevTools protocol: frames (with remembered
# lines), the robot's pose and each driver's state appear, then update. A screenshot of the page
# is kept at $ATLAS_VIEW_SCREENSHOT when set (docs/atlas-view.png is made so). Also: the page
# loads nothing from elsewhere (its Content-Security-Policy), /snapshot.json is JSON, a viewer
# beyond --max-clients gets 503, and SIGTERM stops atlas-view within a second.
# Needs ATLAS_VIEW (and the hil_lib.sh variables). Skips (77) only when chromium is missing.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
need_dataset
CHROMIUM=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
[ -n "$CHROMIUM" ] || { echo "SKIP: chromium is not installed (scripts/install-deps.sh)" >&2; exit 77; }

write_config "$WORK/atlasd.toml" 4
# graph and local map often enough for the page (the defaults are 1 s and 0.2 s).
sed -i 's/^health_period_s = .*/health_period_s = 0.5\ngraph_period_s = 0.5/' "$WORK/atlasd.toml"
"$ATLAS_VIEW" --address 127.0.0.1 --port 0 --max-clients 2 --rate 4 --status-every 5 \
  >"$WORK/view.out" 2>"$WORK/view.err" &
VIEW_PID=$!
PIDS+=("$VIEW_PID")
url=""
for _ in $(seq 50); do
  url=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' "$WORK/view.err" | head -n 1 || true)
  [ -n "$url" ] && break
  kill -0 "$VIEW_PID" 2>/dev/null || fail "atlas-view exited at start: $(cat "$WORK/view.err")"
  sleep 0.1
done
[ -n "$url" ] || fail "atlas-view printed no address"
start_fakedev --speed 4
start_atlasd "$WORK/atlasd.toml"

# The page and its headers.
curl -sS -D "$WORK/page.headers" -o "$WORK/page.html" "$url" || fail "GET / failed"
grep -qi "^content-security-policy: default-src 'none'" "$WORK/page.headers" ||
  fail "no Content-Security-Policy on the page: $(cat "$WORK/page.headers")"
grep -q 'new EventSource("events")' "$WORK/page.html" || fail "the page has no event stream"
! grep -qE 'https?://|<script src|<link' "$WORK/page.html" || fail "the page refers to elsewhere"
pass "the page is one self-contained document"

mkdir -p "$WORK/chromium-profile"
python3 "$(dirname "$0")/browser_check.py" "$CHROMIUM" "$url" "$WORK/chromium-profile" \
  "$WORK/atlas-view.png" 40 | tee "$WORK/browser.out" || {
  echo "--- chromium.err" >&2
  tail -n 20 "$WORK/chromium.err" >&2
  fail "the page in Chromium: $(tail -n 1 "$WORK/browser.out")"
}
[ -s "$WORK/atlas-view.png" ] || fail "no screenshot"
[ -n "${ATLAS_VIEW_SCREENSHOT:-}" ] && cp "$WORK/atlas-view.png" "$ATLAS_VIEW_SCREENSHOT"
pass "Chromium showed frames, pose and health, and they updated"

# The same data once, as JSON.
curl -sS "${url}snapshot.json" >"$WORK/snapshot.json" || fail "GET /snapshot.json failed"
python3 - "$WORK/snapshot.json" <<'PY' || fail "snapshot.json: $(head -c 300 "$WORK/snapshot.json")"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["frames_drawn"] > 0 and d["frames"][0]["id"] == d["source"], d["source"]
assert d["pose"]["placed"], d["pose"]
assert sorted(x["name"] for x in d["health"]["drivers"]) == ["laser", "odometry", "sonar"]
print("snapshot.json: %d frames, %d edges, %d hypotheses, %d bytes" % (
    d["frames_drawn"], len(d["edges"]), len(d["hypotheses"]), len(open(sys.argv[1]).read())))
PY

# Two streams are the limit: the third viewer is refused. (Chromium has gone: its stream ends at
# the first update written after it, 250 ms apart.)
sleep 1.5
curl -sS -N --max-time 10 "${url}events" >"$WORK/events1" 2>/dev/null &
C1=$!
curl -sS -N --max-time 10 "${url}events" >"$WORK/events2" 2>/dev/null &
C2=$!
PIDS+=("$C1" "$C2")
for _ in $(seq 50); do
  grep -q '^data: {' "$WORK/events1" && grep -q '^data: {' "$WORK/events2" && break
  sleep 0.1
done
code=$(curl -sS -o /dev/null -w '%{http_code}' --max-time 3 "${url}events" || true)
[ "$code" = 503 ] || fail "a third viewer got HTTP $code, want 503 (--max-clients 2)"
grep -q '^data: {' "$WORK/events2" || fail "an event stream carried no update"
pass "a viewer beyond --max-clients gets 503; the streams carry updates"
kill "$C1" "$C2" 2>/dev/null || true

kill -0 "$ATLASD_PID" || fail "atlasd died"
stop_pid "$VIEW_PID" 1.5 || fail "atlas-view exited non-zero"
grep -q "atlas-view: streams=" "$WORK/view.err" || fail "no status line from atlas-view"
pass "atlas-view stopped on SIGTERM; $(tail -n 1 "$WORK/view.err")"
stop_pid "$ATLASD_PID" 2.0 || fail "atlasd exited non-zero"
