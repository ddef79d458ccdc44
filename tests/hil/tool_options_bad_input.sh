#!/usr/bin/env bash
# The tools' number options on bad values (no network, no input files: every value is refused
# while the command line is read): a value with trailing characters, an empty one, a non-finite
# one and one out of range are refused with exit 2 and core/common/parse_number.h's message,
# which names the option, the range and the text given. Needs ATLASD, ATLAS_REPLAY,
# ATLAS_RENDER, ATLAS_REFINE, ATLAS_EXPORT, ATLAS_EVAL, ATLAS_CARMEN, ATLAS_VIEW.
source "$(dirname "$0")/hil_lib.sh"
: "${ATLASD:?}" "${ATLAS_REPLAY:?}" "${ATLAS_RENDER:?}" "${ATLAS_REFINE:?}" "${ATLAS_EVAL:?}"
: "${ATLAS_CARMEN:?}" "${ATLAS_EXPORT:?}" "${ATLAS_VIEW:?}"

# refused TOOL OPTION KIND RANGE OUT_OF_RANGE: TOOL OPTION VALUE exits 2 with "OPTION must be
# a KIND in RANGE, got 'VALUE'" for each bad VALUE.
refused() {
  local tool=$1 option=$2 kind=$3 range=$4 out=$5 v
  for v in 5x '' nan 1e999 "$out"; do
    expect_exit 2 "^[a-z-]+: $option must be an? $kind in \\$range, got '$v'" \
      "$tool" "$option" "$v"
  done
  expect_exit 2 "$option needs a" "$tool" "$option"
}

refused "$ATLAS_RENDER" --budget number '[0, 1000000000]' 1e10
refused "$ATLAS_RENDER" --projection integer '[0, 2147483647]' -1
refused "$ATLAS_RENDER" --width integer '[200, 20000]' 199
refused "$ATLAS_RENDER" --scans integer '[0, 1000000]' 1000001
refused "$ATLAS_RENDER" --odometry-km number '[0, 1000000]' -0.5
pass "atlas-render's number options"

refused "$ATLAS_VIEW" --port integer '[0, 65535]' 65536
refused "$ATLAS_VIEW" --rate number '[0.1, 10]' 0
refused "$ATLAS_VIEW" --max-clients integer '[1, 64]' 65
refused "$ATLAS_VIEW" --max-frames integer '[1, 100000]' 0
refused "$ATLAS_VIEW" --status-every number '[0, 86400]' -1
pass "atlas-view's number options"

R=$ATLAS_REPLAY
refused "$R" --max-scans integer '[1, 9223372036854775807]' 0
refused "$R" --restart-after-scans integer '[1, 9223372036854775807]' 0
refused "$R" --laser-max-range number '[0.01, 1000000]' 0
refused "$R" --map-capacity integer '[1, 10000]' 10001
refused "$R" --max-hypotheses integer '[1, 1000]' 0
refused "$R" --laser-time-offset number '[-1, 1]' 1.5
refused "$R" --seed integer '[0, 18446744073709551615]' 18446744073709551616
refused "$R" --wheel-noise number '[0, 1]' -1e-9
refused "$R" --left-scale-error number '[-0.5, 0.5]' 0.6
refused "$R" --right-scale-error number '[-0.5, 0.5]' -0.6
refused "$R" --track-width-error number '[-0.5, 0.5]' 1
refused "$R" --line-period number '[1e-06, 1]' 0
refused "$R" --log-max-range number '[0, 1000000]' -1
for v in 5x:0:0.1 -0.2:0:0.1x -0.2::0.1 1e999:0:0.1 nan:0:0.1 -0.2:0; do
  expect_exit 2 "--sweep-laser-time-offset: want FROM:TO:STEP in seconds .*got '$v'" \
    "$R" --sweep-laser-time-offset "$v"
done
expect_exit 2 "--sweep-laser-time-offset: offsets must lie within -1 s and \+1 s \(got '-2:0:0.1'\)" \
  "$R" --sweep-laser-time-offset -2:0:0.1
pass "atlas-replay's number options"

refused "$ATLAS_REFINE" --max-iterations integer '[1, 100000]' 100001
pass "atlas-refine's number options"

refused "$ATLAS_EXPORT" --reference integer '[0, 100000000]' -1
refused "$ATLAS_EXPORT" --resolution number '[0.01, 10]' 0.001
pass "atlas-export's number options"

refused "$ATLASD" --health-every number '[0.001, 86400]' 0
pass "atlasd's number options"

refused "$ATLAS_EVAL" --tolerance number '[0, 1000000]' -0.001
refused "$ATLAS_EVAL" --segment number '[0.001, 1000000]' 0
refused "$ATLAS_EVAL" --step integer '[1, 1000000000]' 0
pass "atlas-eval's number options"

C=$ATLAS_CARMEN
refused "$C" --seed integer '[0, 18446744073709551615]' -1
refused "$C" --line-period number '[1e-06, 1]' 2
refused "$C" --log-max-range number '[0, 1000000]' -1
refused "$C" --track-width number '[0.05, 10]' 0
refused "$C" --wheel-noise number '[0, 1]' 1.5
refused "$C" --left-scale-error number '[-0.5, 0.5]' 0.6
refused "$C" --right-scale-error number '[-0.5, 0.5]' -0.6
refused "$C" --track-width-error number '[-0.5, 0.5]' 1
pass "atlas-carmen's number options"
