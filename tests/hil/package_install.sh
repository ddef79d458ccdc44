#!/usr/bin/env bash
# HIL (package): the Debian package of this build tree on this machine, as a user would have it.
#   1. cpack makes the package; lintian finds no error or warning in it; dpkg -i installs it;
#   2. systemd-analyze verifies the installed unit; the installed atlasd checks the installed
#      /etc/atlasd/atlasd.toml (a conffile);
#   3. the installed atlas-sim makes a run, the installed atlas-fakedev plays it, and the
#      installed atlasd (started directly, no systemctl) maps it with the installed
#      configuration adapted to the fakes, publishing poses on LCM; SIGTERM stops it cleanly;
#   4. dpkg -P removes the package: no file or directory of it is left.
# The package is purged on every exit, also on failure. Needs root, dpkg and cpack; skipped (77)
# when an atlasd package is already installed here (never replaces a real installation).
# Needs BUILD_DIR (the build tree to package) in the environment.
source "$(dirname "$0")/hil_lib.sh"
need_multicast
skip() {
  echo "SKIP: $*" >&2
  exit 77
}
[ "$(id -u)" = 0 ] || skip "needs root (dpkg -i)"
command -v dpkg >/dev/null && command -v cpack >/dev/null && command -v lintian >/dev/null ||
  skip "needs dpkg, cpack and lintian"
[ -f "$BUILD_DIR/CPackConfig.cmake" ] || fail "no CPackConfig.cmake in BUILD_DIR=$BUILD_DIR"
if dpkg-query -W -f='${db:Status-Status}' atlasd 2>/dev/null | grep -qv '^not-installed$'; then
  skip "an atlasd package is already installed on this machine ($(dpkg-query -W -f='${Version} ${db:Status-Status}' atlasd))"
fi

INSTALLED=0
purge() {
  if [ "$INSTALLED" = 1 ]; then
    dpkg -P atlasd >"$WORK/purge.out" 2>&1 || { echo "dpkg -P atlasd failed:" >&2; cat "$WORK/purge.out" >&2; }
    INSTALLED=0
  fi
}
trap 'purge; cleanup' EXIT

# 1. Package and install. (Debian's python3, which reads /usr/lib/python3/dist-packages.)
cpack --config "$BUILD_DIR/CPackConfig.cmake" -B "$WORK/pkg" >"$WORK/cpack.err" 2>&1 ||
  fail "cpack failed: $(tail -n 20 "$WORK/cpack.err")"
debs=("$WORK"/pkg/atlasd_*.deb)
[ ${#debs[@]} = 1 ] && [ -f "${debs[0]}" ] || fail "cpack made no single atlasd_*.deb: ${debs[*]}"
deb=${debs[0]}
# Debian's checks of the package: no error and no warning (its overrides are in the package).
lintian --fail-on error,warning "$deb" >"$WORK/lintian.out" 2>&1 ||
  fail "lintian: $(grep -v 'root privileges' "$WORK/lintian.out" | head -n 20)"
dpkg-deb --fsys-tarfile "$deb" | tar -t | sed -e 's|^\./|/|' -e 's|/$||' | grep -v '^/\?$' \
  >"$WORK/contents"
INSTALLED=1
dpkg -i "$deb" >"$WORK/dpkg-i.err" 2>&1 || fail "dpkg -i failed: $(tail -n 20 "$WORK/dpkg-i.err")"
for f in /usr/bin/atlasd /usr/bin/atlas-fakedev /usr/bin/atlas-sim /usr/bin/atlas-lcm-log-summary \
  /usr/share/man/man8/atlasd.8.gz /lib/systemd/system/atlasd.service /usr/include/atlasd/pose_t.hpp \
  /usr/share/atlasd/lcmtypes/pose_t.lcm /usr/lib/python3/dist-packages/atlasd/pose_t.py \
  /usr/share/doc/atlasd/copyright /usr/share/doc/atlasd/examples/80-atlasd-can0.network; do
  [ -e "$f" ] || fail "the package did not install $f"
done
grep -q '^ExecStart=/usr/bin/atlasd ' /lib/systemd/system/atlasd.service ||
  fail "the installed unit does not run /usr/bin/atlasd"
if command -v systemd-analyze >/dev/null; then
  systemd-analyze verify /lib/systemd/system/atlasd.service >"$WORK/verify.err" 2>&1 ||
    fail "systemd-analyze verify of the installed unit: $(cat "$WORK/verify.err")"
fi
dpkg-query -W -f='${Conffiles}\n' atlasd | grep -q '^ /etc/atlasd/atlasd.toml ' ||
  fail "/etc/atlasd/atlasd.toml is not a conffile: $(dpkg-query -W -f='${Conffiles}' atlasd)"
PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -c 'from atlasd import pose_t
p = pose_t(); p.x = 1.5
assert pose_t.decode(p.encode()).x == 1.5' 2>"$WORK/python.err" ||
  fail "the installed Python types do not round-trip: $(cat "$WORK/python.err")"
pass "cpack made $(basename "$deb") ($(wc -l <"$WORK/contents") entries); dpkg -i installed it"

# 2. The installed configuration is valid as shipped.
expect_exit 0 'configuration is valid' /usr/bin/atlasd --check-config /etc/atlasd/atlasd.toml
pass "atlasd --check-config /etc/atlasd/atlasd.toml: valid"

# 3. The installed atlasd on the installed fakes, with the installed configuration adapted:
#    devices (the first "enabled = false" is the sonar's), the simulator's track width, the speed allowance, LCM, state, no real-time.
SPEED=4
/usr/bin/atlas-sim --rooms 4 --length-km 0.06 --seed 3 --quiet --out "$WORK/sim" \
  >"$WORK/sim.out" 2>"$WORK/sim.err" || fail "the installed atlas-sim failed"
adapt() {  # adapt 'KEY = OLD' 'KEY = NEW': one line of the installed file, which must be there
  grep -qxF "$1" "$WORK/atlasd.toml" || fail "no line '$1' in the installed atlasd.toml"
  awk -v old="$1" -v new="$2" '$0 == old && !done { print new; done = 1; next } { print }' \
    "$WORK/atlasd.toml" >"$WORK/atlasd.toml.new"
  mv "$WORK/atlasd.toml.new" "$WORK/atlasd.toml"
}
cp /etc/atlasd/atlasd.toml "$WORK/atlasd.toml"
adapt 'device = "/dev/ttyUSB0"' "device = \"$WORK/dev/laser\""
adapt 'unit = "mm"' 'unit = "cm"'
adapt 'max_range_m = 8.0' 'max_range_m = 30.0'
adapt 'device = "/dev/ttyS0"' "device = \"$WORK/dev/sonar\""
adapt 'enabled = false' 'enabled = true'
adapt 'interface = "can0"' "interface = \"unix:$WORK/dev/can\""
adapt 'track_width_m = 0.58' 'track_width_m = 0.4'
adapt 'max_speed_mps = 3.0' "max_speed_mps = $((3 * SPEED))"
adapt 'slack_m = 0.02' "slack_m = $(awk -v s=$SPEED 'BEGIN { print 0.02 * s }')"
adapt 'url = "udpm://239.255.76.67:7667?ttl=0"' "url = \"$LCM_DEFAULT_URL\""
adapt 'directory = "/var/lib/atlasd"' "directory = \"$WORK/state\""
adapt 'policy = "fifo"' 'policy = "other"'
adapt 'priority = 40' 'priority = 0'
expect_exit 0 'configuration is valid' /usr/bin/atlasd --check-config "$WORK/atlasd.toml"

FAKEDEV=/usr/bin/atlas-fakedev DATASET="$WORK/sim/run.clf" start_fakedev --speed "$SPEED"
start_logger
ATLASD=/usr/bin/atlasd start_atlasd "$WORK/atlasd.toml" --quiet
wait "$FAKEDEV_PID" || fail "atlas-fakedev failed: $(tail -n 3 "$WORK/fakedev.err")"
sleep 1
kill -0 "$ATLASD_PID" 2>/dev/null || fail "the installed atlasd exited early"
stop_pid "$ATLASD_PID" 5 || fail "the installed atlasd did not exit 0 on SIGTERM"
sleep 0.3
stop_logger
/usr/bin/atlas-lcm-log-summary "$WORK/session.lcm" >"$WORK/summary.txt" 2>"$WORK/summary.err" ||
  fail "atlas-lcm-log-summary failed: $(cat "$WORK/summary.err")"
poses=$(summary_value "$WORK/summary.txt" pose.count)
steps=$(summary_value "$WORK/summary.txt" health.last_steps)
[ "${poses:-0}" -gt 50 ] || fail "the installed atlasd published ${poses:-no} poses, want > 50"
[ "${steps:-0}" -gt 10 ] || fail "the installed atlasd stepped ${steps:-no} scans, want > 10"
[ -f "$WORK/state/atlas.sqlite" ] || fail "the installed atlasd saved no atlas"
pass "the installed atlasd on the installed fakes: $poses poses, $steps steps, atlas saved, stopped cleanly"

# 4. Purge: nothing of the package stays (directories shared with other packages do).
INSTALLED=0
dpkg -P atlasd >"$WORK/purge.out" 2>&1 || fail "dpkg -P atlasd failed: $(cat "$WORK/purge.out")"
dpkg-query -W -f='${db:Status-Status}' atlasd 2>/dev/null | grep -qv '^not-installed$' &&
  fail "dpkg still knows atlasd after the purge"
left=()
while IFS= read -r f; do
  [ -e "$f" ] || [ -L "$f" ] || continue
  # A directory stays when another package owns it too (/usr/bin, /usr/share/man/man1 ...) or
  # holds other files (/lib, a link to /usr/lib on a merged /usr).
  if [ -d "$f" ]; then
    dpkg -S "$f" >/dev/null 2>&1 && continue
    [ -n "$(ls -A "$f/")" ] && continue
  fi
  left+=("$f")
done <"$WORK/contents"
for f in /etc/atlasd /usr/share/doc/atlasd /usr/share/atlasd /usr/include/atlasd \
  /usr/lib/python3/dist-packages/atlasd; do
  [ -e "$f" ] && left+=("$f")
done
[ ${#left[@]} = 0 ] || fail "left after dpkg -P atlasd: ${left[*]}"
pass "dpkg -P atlasd: none of the $(wc -l <"$WORK/contents") entries of the package is left"
