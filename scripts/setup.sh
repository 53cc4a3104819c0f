#!/usr/bin/env bash
# Installs the Debian 12 packages slamkit needs (only those missing) and builds it.
# Usage: scripts/setup.sh [release|asan] [TARGET ...]   (default: release, every target).
# Idempotent and quick when done: compiler outputs are cached by ccache (~/.cache/ccache, keyed
# on paths relative to the checkout, so a second clone reuses them).
#   release  GCC, -O3: the library, the `slamkit` program, the tests and the benchmarks.
#   asan     clang with AddressSanitizer and UndefinedBehaviorSanitizer at -O1 (asserts and
#            Eigen's index checks on; test code at -O0): the tests not labelled `slow` or
#            needing the program (test.sh runs those in Release only), each test program
#            registered with ctest as one test (SLAMKIT_TEST_PER_PROGRAM), and the libFuzzer
#            harnesses of the input readers (fuzz/, scripts/fuzz.sh), all in one tree.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake ninja-build pkg-config ccache libeigen3-dev libgtest-dev libgmock-dev
          libbenchmark-dev libcli11-dev libyaml-cpp-dev libfmt-dev libspdlog-dev
          nlohmann-json3-dev libtbb-dev libboost-dev libboost-math-dev libboost-iostreams-dev
          zlib1g-dev libpng-dev libmgl-dev libceres-dev time clang libclang-rt-14-dev
          librosbag-dev pluginlib-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev
          python3-rosbag python3-sensor-msgs python3-nav-msgs python3-tf2-msgs
          pybind11-dev python3-dev python3-numpy python3-pytest chromium)
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
[ $# -gt 0 ] && shift
targets=("$@")
env_args=()
case "$flavour" in
  release) args=(-DCMAKE_BUILD_TYPE=Release -DSLAMKIT_BUILD_PYTHON=ON) ;;
  # -O1 rather than Debug's -O0: the same tests ran 15 times slower at -O0 under ASan than in
  # Release, and -O1 is what the sanitizers' authors advise; -g1 keeps file and line in every
  # report at a fraction of full debug information's compile and link time. clang, because
  # libFuzzer is part of clang: one sanitizer build serves the tests and the harnesses (a
  # separate fuzz build compiled every library a third time). Not -march=native:
  # SLAMKIT_SANITIZE turns SLAMKIT_NATIVE's default off (CMakeLists.txt). The libraries in unity
  # batches of 64 files rather than 16: they took 16 % less CPU (250 s against 296 s of user
  # time up to slamkit_runners, no ccache), and compiling is most of the test command's time
  # from a fresh clone.
  asan)
    env_args=(CC=clang CXX=clang++)
    args=(-DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" -DSLAMKIT_BUILD_FUZZ=ON
          -DSLAMKIT_BUILD_BENCH=OFF -DSLAMKIT_BUILD_SLOW_TESTS=OFF -DSLAMKIT_BUILD_APPS=OFF
          -DSLAMKIT_TEST_PER_PROGRAM=ON -DSLAMKIT_UNITY_BATCH_SIZE=64) ;;
  *) echo "setup: unknown build '$flavour' (release|asan)" >&2; exit 2 ;;
esac
build=build/$flavour
# Configured afresh when the tree is new or was configured with other settings (an older
# checkout's asan build was GCC's): the settings are kept beside the tree.
settings="${env_args[*]} ${args[*]}"
previous=$(cat "$build/setup-settings" 2>/dev/null || true)
if [ ! -f "$build/build.ninja" ] || [ "$previous" != "$settings" ]; then
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
  env "${env_args[@]}" cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
    "${args[@]}"
  echo "$settings" >"$build/setup-settings"
fi
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=1
cmake --build "$build" -j "$(nproc)" ${targets[@]:+--target "${targets[@]}"}
