#!/usr/bin/env bash
# Sets everything up, then runs the whole test suite: the Release build's tests, the installed
# package (examples/cpp built against it), then the sanitizer build (ASan and UBSan at -O1; tests
# labelled `slow` run in Release only), then a short libFuzzer smoke run of every input reader's
# harness (fuzz/, scripts/fuzz.sh). Each step prints its time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
step() { echo "test: $1 done at $((SECONDS - start)) s"; }
scripts/setup.sh release
step "release build"
(cd build/release && ctest --output-on-failure -j "$(nproc)")
step "release tests"
# The installed package: install the Release tree into build/release/install, build examples/cpp
# against it (find_package(slamkit)) and run both programs.
prefix=$PWD/build/release/install
cmake --install build/release --prefix "$prefix"
cmake -S examples/cpp -B build/examples -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build build/examples -j "$(nproc)"
for program in ekf_landmarks grid_laser; do
  output=$(build/examples/$program)
  printf '%s:\n%s\n' "$program" "$output"
  grep -q "^final pose:" <<<"$output" || { echo "test: $program printed no final pose" >&2; exit 1; }
done
step "installed package"
scripts/setup.sh asan
step "sanitizer build"
(cd build/asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j "$(nproc)" -LE slow)
step "sanitizer tests"
# 20 s per harness, as many at once as there are cores: long enough to catch a reader change that
# crashes on its seed corpus or on simple mutations of it; real campaigns are scripts/fuzz.sh
# READER 600. Each run prints its own result line; xargs fails when any of them does.
scripts/setup.sh fuzz
step "fuzz build"
ls fuzz/corpus | xargs -P "$(nproc)" -I{} scripts/fuzz.sh {} 20  # a corpus folder per harness
step "fuzz smoke"
