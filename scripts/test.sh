#!/usr/bin/env bash
# Sets everything up, then runs the whole test suite, each test in the build where it tells
# something: in the sanitizer build (clang, ASan and UBSan at -O1, asserts on) every test but
# those labelled `slow` and those that run the program; in the Release build (GCC, -O3,
# -march=native: what users run) the slow ones and those labelled `release` (the toolchain and
# processor checks, the command-line tests), then the installed package (examples/cpp built
# against it; the Python module's tests and examples); last, a short libFuzzer smoke run of every
# input reader's harness (fuzz/, scripts/fuzz.sh) from the sanitizer build. Each step prints its
# time.
# `ctest` in build/release runs every test in Release too, and the benchmarks (bench/) are there,
# after `scripts/setup.sh release`, which builds every target; this command leaves them out to
# stay within its time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
step() { echo "test: $1 done at $((SECONDS - start)) s"; }
scripts/setup.sh release slamkit slamkit_release_tests slamkit_python
step "release build"
(cd build/release && ctest --output-on-failure -j "$(nproc)" -L 'slow|release')
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
# The Python module as installed (lib/python3.X/dist-packages under the prefix), under Debian's
# python3 with its numpy and pytest: the tests against the program, then the two examples.
site=$(/usr/bin/python3 -c 'import sys; print("python%d.%d" % sys.version_info[:2])')
export PYTHONPATH=$prefix/lib/$site/dist-packages SLAMKIT_CLI=$PWD/build/release/bin/slamkit
/usr/bin/python3 -m pytest -q -p no:cacheprovider python/tests
for example in examples/python/*.py; do /usr/bin/python3 "$example"; done
unset PYTHONPATH SLAMKIT_CLI
step "installed package"
scripts/setup.sh asan
step "sanitizer build"
(cd build/asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j "$(nproc)" -LE slow)
step "sanitizer tests"
# 2 s per harness (over a thousand inputs each), as many at once as there are cores: long enough to
# catch a reader change that crashes on its seed corpus or on simple mutations of it; real
# campaigns are scripts/fuzz.sh READER 600. Each run prints its own result line; xargs fails when
# any of them does.
ls fuzz/corpus | xargs -P "$(nproc)" -I{} scripts/fuzz.sh {} 2  # a corpus folder per harness
step "fuzz smoke"
