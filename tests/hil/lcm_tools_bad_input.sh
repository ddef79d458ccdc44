#!/usr/bin/env bash
# The LCM log tools on bad input (no network: logs are written byte by byte here, atlasd
# --replay reads a file, atlas-pose-latency is refused before it opens LCM): atlas-lcm-log-summary
# refuses a directory, an empty file, random bytes and a CARMEN log; atlasd --replay (which
# reads CARMEN logs too) refuses the first three; both report a truncated or corrupt log and
# undecodable events with the byte and a non-zero exit; options are validated (exit 2). Needs
# ATLASD, LOG_SUMMARY, POSE_LATENCY.
source "$(dirname "$0")/hil_lib.sh"
: "${ATLASD:?}" "${LOG_SUMMARY:?}" "${POSE_LATENCY:?}"
export LCM_DEFAULT_URL=memq://

# expect RC PATTERN CMD...: expect_exit, and LCM's own reader never speaks for ours.
expect() {
  expect_exit "$@"
  if grep -q "invalid channel length" "$WORK/err" && ! grep -q "corrupt at byte" "$WORK/err"; then
    fail "${*:3} -> LCM's own reader message: $(cat "$WORK/err")"
  fi
}

be32() { printf "\\x$(printf %02x $((($1 >> 24) & 255)))\\x$(printf %02x $((($1 >> 16) & 255)))\\x$(printf %02x $((($1 >> 8) & 255)))\\x$(printf %02x $(($1 & 255)))"; }
# event CHANNEL DATA [CHANNEL_LENGTH]: one lcm-logger event (event number and timestamp 0).
event() {
  printf '\xED\xA1\xDA\x01'
  be32 0; be32 0; be32 0; be32 0
  be32 "${3:-${#1}}"
  be32 "${#2}"
  printf '%s%s' "$1" "$2"
}

S=$LOG_SUMMARY
{ event X ab; event X cd; } >"$WORK/ok.lcm"                # 2 events of 31 bytes
{ event X ab; event X cd -1; } >"$WORK/corrupt.lcm"
head -c 59 "$WORK/ok.lcm" >"$WORK/cut.lcm"
{ event X ab; event ATLAS_POSE xyz; } >"$WORK/undecodable.lcm"
: >"$WORK/empty.lcm"
printf '\x13\x37\x00\xff\x42random bytes' >"$WORK/random.bin"
printf '# CARMEN Logfile\nODOM 0 0 0 0 0 0 1.0 host 1.0\n' >"$WORK/mit.clf"

# atlas-lcm-log-summary
expect 0 '^Usage: atlas-lcm-log-summary' "$S" --help
expect 2 'no LOGFILE given' "$S"
expect 2 "unknown option '--bogus-opt'" "$S" --bogus-opt
expect 2 "unknown option '--bogus'" "$S" "$WORK/ok.lcm" --bogus
expect 2 '--poses needs a value' "$S" "$WORK/ok.lcm" --poses
expect 2 "unexpected argument '$WORK/ok.lcm'" "$S" "$WORK/ok.lcm" "$WORK/ok.lcm"
expect 1 'is a directory' "$S" "$WORK"
expect 1 'is empty, not an LCM log' "$S" "$WORK/empty.lcm"
expect 1 'not an LCM log: it begins with 13 37 00 FF' "$S" "$WORK/random.bin"
expect 1 'a CARMEN log\?' "$S" "$WORK/mit.clf"
expect 1 'cannot read the LCM log \(No such file' "$S" "$WORK/missing.lcm"
expect 1 'truncated at byte 59: the last event, event 2 \(from byte 31\), is incomplete' "$S" "$WORK/cut.lcm"
grep -qx 'events.X=1' "$WORK/out" && grep -qx 'log=truncated' "$WORK/out" || fail "cut.lcm: $(cat "$WORK/out")"
expect 1 'corrupt at byte 31: event 2 \(from byte 31\) has an invalid channel length -1' "$S" "$WORK/corrupt.lcm"
grep -qx 'log=corrupt' "$WORK/out" || fail "corrupt.lcm: $(cat "$WORK/out")"
expect 1 '1 event on ATLAS_POSE could not be decoded' "$S" "$WORK/undecodable.lcm"
grep -qx 'undecodable.ATLAS_POSE=1' "$WORK/out" || fail "undecodable.lcm: $(cat "$WORK/out")"
expect 1 'cannot write the poses file /nonexistent/p \(No such file' "$S" "$WORK/ok.lcm" --poses /nonexistent/p
expect 0 '^events.X=2$' "$S" "$WORK/ok.lcm" --poses "$WORK/poses.txt"
grep -qx 'log=complete' "$WORK/out" || fail "ok.lcm: $(cat "$WORK/out")"
[ -f "$WORK/poses.txt" ] || fail "no poses file written"

# atlasd --replay, with the defaults
printf '# defaults\n' >"$WORK/atlasd.toml"
R=("$ATLASD" --config "$WORK/atlasd.toml" --replay)
# (a file that does not begin with the LCM sync word is read as a CARMEN log)
for f in "$WORK" "$WORK/empty.lcm" "$WORK/random.bin"; do
  expect 1 "atlasd: replay: $f" "${R[@]}" "$f" --out "$WORK/r"
done
[ ! -e "$WORK/r" ] || fail "atlasd --replay made $WORK/r for a file it refused"
expect 1 'truncated at byte 59' "${R[@]}" "$WORK/cut.lcm" --out "$WORK/r"
[ -f "$WORK/r/trajectory.tsv" ] || fail "no trajectory.tsv for the events before the cut"
expect 1 'corrupt at byte 31' "${R[@]}" "$WORK/corrupt.lcm" --out "$WORK/r"
expect 1 'nothing to step: .*\(2 LCM events\)' "${R[@]}" "$WORK/ok.lcm" --out "$WORK/r"
# a CARMEN log with odometry only: read, nothing to step
expect 1 'nothing to step: .*a CARMEN log' "${R[@]}" "$WORK/mit.clf" --out "$WORK/c"

# atlas-pose-latency: options (refused before LCM is opened)
P=$POSE_LATENCY
expect 0 '^Usage: atlas-pose-latency' "$P" --help
for v in abc 5x 1e300 1e999 nan 0 -5 100000 ''; do
  expect 2 "--seconds must be a number in \[0.001, 86400\], got '$v'" "$P" --seconds "$v"
done
for v in abc 5x '' -1 1.5 1e3 nan 2000000; do
  expect 2 "--warmup must be an integer in \[0, 1000000\], got '$v'" "$P" --warmup "$v"
done
expect 2 '--seconds needs a value' "$P" --seconds
expect 2 "--channel needs a NAME, got ''" "$P" --channel ''
expect 2 '--channel needs a value' "$P" --channel=
expect 2 "unknown option '--bogus'" "$P" --bogus

pass "the LCM log tools on bad input"
