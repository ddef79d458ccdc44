#!/usr/bin/env bash
# Installs the Debian 12 packages atlasd needs to build, test and run. Does nothing when they
# are all installed already. Safe to run from any directory.
#
# Usage: scripts/install-deps.sh   (no arguments; -h, --help: this text)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/script-usage.sh"
script_usage "${BASH_SOURCE[0]}" none "$@"

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev                 # linear algebra (core/)
  liblcm-dev liblcm-bin liblcm-java  # LCM: messages, lcm-gen, lcm-logger, lcm.jar
  default-jdk-headless          # javac/jar for the LCM Java types; runs atlas-spy
  libjchart2d-java              # charts used by lcm.spy.Spy
  libcairo2-dev libfontconfig-dev  # pictures (PNG, SVG); fontconfig to free its caches at exit
  zlib1g-dev                    # gzip CARMEN logs
  libtomlplusplus-dev           # the configuration file
  libcli11-dev                  # every tool's command line (tools/cli), header-only
  libsqlite3-dev                # the persistent atlas store
  libsystemd-dev                # sd_notify
  libceres-dev                  # offline global refinement
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev      # libFuzzer targets
  iproute2 util-linux           # private network namespaces for the hardware-in-loop tests
  xvfb xauth imagemagick        # lcm-spy under a virtual display, and its screenshot
  systemd                       # systemd-analyze verify
  help2man dpkg-dev file        # the Debian package: man pages from --help, cpack's shlibdeps
  lintian                       # the package's test: Debian's checks
  libcpp-httplib-dev            # atlas-view's HTTP server (one page, server-sent events)
  chromium curl                 # atlas-view's browser test: headless Chromium, and HTTP checks
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q >&2
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
