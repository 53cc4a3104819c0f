#!/usr/bin/env bash
# Sets everything up, then runs the whole test suite: the Release build, then a Debug build with
# AddressSanitizer and UndefinedBehaviorSanitizer (tests labelled `slow` run in Release only).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release
(cd build/release && ctest --output-on-failure -j "$(nproc)")
scripts/setup.sh asan
(cd build/asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j "$(nproc)" -LE slow)
