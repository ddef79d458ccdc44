# Sourced by the evaluation scripts: release_bin TARGET... prints the directory of the tools to
# run: ATLAS_BIN (default <repo>/build/release/bin) when every TARGET is there, else
# <repo>/build/release/bin after building the missing ones there (RelWithDebInfo).
release_bin() {
  local root bin t
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  bin=${ATLAS_BIN:-$root/build/release/bin}
  for t in "$@"; do
    if [[ ! -x $bin/$t ]]; then
      cmake -S "$root" -B "$root/build/release" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
      cmake --build "$root/build/release" -j2 --target "$@" >/dev/null
      bin=$root/build/release/bin
      break
    fi
  done
  echo "$bin"
}
