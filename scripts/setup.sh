#!/usr/bin/env bash
# Installs the Debian 12 packages slamkit needs (only those missing) and builds it.
# Usage: scripts/setup.sh [release|asan|fuzz]   (default: release). Idempotent and quick when done.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake ninja-build pkg-config libeigen3-dev libgtest-dev libgmock-dev
          libbenchmark-dev libcli11-dev libyaml-cpp-dev libfmt-dev libspdlog-dev
          nlohmann-json3-dev libtbb-dev libboost-dev libboost-math-dev libboost-iostreams-dev
          zlib1g-dev libpng-dev libmgl-dev time clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

flavour=${1:-release}
env_args=()
case "$flavour" in
  release) args=(-DCMAKE_BUILD_TYPE=Release) ;;
  asan) args=(-DCMAKE_BUILD_TYPE=Debug -DSLAMKIT_SANITIZE=ON -DSLAMKIT_BUILD_BENCH=OFF) ;;
  # The libFuzzer harnesses (fuzz/, run by scripts/fuzz.sh): clang with ASan and UBSan, only the
  # libraries and the harnesses. RelWithDebInfo with the flags given here rather than its default
  # ones: -O2 runs several times more inputs per second than Debug's -O0 does under ASan, and
  # leaving out -DNDEBUG keeps assert() and Eigen's index checks, which find bugs that -O2 alone
  # would let pass silently.
  fuzz)
    env_args=(CC=clang CXX=clang++)
    args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g"
          -DSLAMKIT_BUILD_FUZZ=ON -DSLAMKIT_BUILD_TESTS=OFF -DSLAMKIT_BUILD_BENCH=OFF
          -DSLAMKIT_BUILD_APPS=OFF -DSLAMKIT_BUILD_REPORT=OFF) ;;
  *) echo "setup: unknown build '$flavour' (release|asan|fuzz)" >&2; exit 2 ;;
esac
build=build/$flavour
if [ ! -f "$build/build.ninja" ]; then
  env "${env_args[@]}" cmake -S . -B "$build" -G Ninja "${args[@]}"
fi
cmake --build "$build" -j "$(nproc)"
