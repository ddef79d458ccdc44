#!/usr/bin/env bash
# The tools' number options on bad values (no network, no input files: every value is refused
# while the command line is read): a value with trailing characters, an empty one, a non-finite
# one and one out of range are refused with exit 2 and core/common/parse_number.h's message,
# which names the option, the range and the text given. Needs ATLAS_RENDER.
source "$(dirname "$0")/hil_lib.sh"
: "${ATLAS_RENDER:?}"

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

