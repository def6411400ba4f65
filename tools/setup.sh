#!/usr/bin/env bash
# netsculpt's one entry point on a fresh Debian 12 machine (as root, or with sudo).
#   tools/setup.sh demo   install what is missing, build, run the default sculpture into out/demo/
#   tools/setup.sh test   install what is missing, build, run every test (what .ci/run does)
#   tools/setup.sh build  install what is missing and build
# Environment: NETSCULPT_BUILD_DIR (default build), NETSCULPT_JOBS (default: all cores),
#              NETSCULPT_WERROR=ON to make warnings errors (CI).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${NETSCULPT_BUILD_DIR:-$here/build}"
jobs="${NETSCULPT_JOBS:-$(nproc)}"

packages=(
  build-essential cmake ninja-build ccache pkg-config
  catch2 liblua5.4-dev lua5.4 libeigen3-dev libbullet-dev libsuitesparse-dev
  libcli11-dev libfmt-dev nlohmann-json3-dev libdxflib-dev libtinygltf-dev libstb-dev
  libglfw3-dev libimgui-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri mesa-utils python3-ezdxf
)

install_missing() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "netsculpt: installing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

configure_and_build() {
  cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DNETSCULPT_WERROR="${NETSCULPT_WERROR:-OFF}" >/dev/null
  cmake --build "$build" -j "$jobs"
}

run_demo() {
  local out="$here/out/demo"
  mkdir -p "$out"
  "$build/tools/netsculpt" run "$here/scripts/default.lua" --out "$out"
  echo "netsculpt: the default sculpture's outputs are in $out"
}

run_tests() {
  cd "$build"
  ctest --output-on-failure -j "$jobs" --timeout 600
}

case "${1:-}" in
  demo) install_missing; configure_and_build; run_demo ;;
  test) install_missing; configure_and_build; run_tests ;;
  build) install_missing; configure_and_build ;;
  *) echo "usage: tools/setup.sh demo|test|build" >&2; exit 2 ;;
esac
