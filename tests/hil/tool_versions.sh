#!/usr/bin/env bash
# Every tool given on the command line answers --version with one line "NAME VERSION" on
# stdout and exit 0, NAME being the file name, and all tools print the same VERSION (the
# project version and, in a git checkout, the commit: core/common/version.h).
# Usage: tool_versions.sh TOOL...
source "$(dirname "$0")/hil_lib.sh"
[ $# -gt 0 ] || fail "no tools given"
first=""
for tool in "$@"; do
  name=$(basename "$tool")
  out=$("$tool" --version) || fail "$name --version exited $?"
  [ "$(printf '%s\n' "$out" | wc -l)" = 1 ] || fail "$name --version: more than one line: $out"
  [[ $out =~ ^$name\ ([0-9]+\.[0-9]+\.[0-9]+( \(git [^ ()]+\))?)$ ]] ||
    fail "$name --version printed '$out'"
  version=${BASH_REMATCH[1]}
  [ -z "$first" ] && first=$version
  [ "$version" = "$first" ] || fail "$name says $version, the first tool $first"
done
pass "$# tools: --version says $first"
