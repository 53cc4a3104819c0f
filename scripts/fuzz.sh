#!/usr/bin/env bash
# Runs a libFuzzer campaign on one reader's harness (fuzz/), or on each in turn with `all`.
# Usage: scripts/fuzz.sh READER|all SECONDS   (READER: carmen, carmen_gz, relations, isam,
#        landmark_csv, scenario, floor_plan, waypoints, occupancy_image, trajectory,
#        suite_manifest, mrclam, pose_graph)
# Needs the sanitizer build (scripts/setup.sh asan), which holds the harnesses. Starts from the
# seeds in fuzz/corpus/READER, copied into build/asan/corpus-work/READER, which the fuzzer grows
# (the repository's seeds stay as they are; the working corpus is kept between runs so that
# campaigns build on each other).
# Prints the executions and the result; exits non-zero on any finding (a crash, an exception
# other than InputError, a sanitizer report, a leak, an input slower than 2 s, more than 2 GB).
# The input that failed goes to build/asan/artifacts/READER/, the fuzzer's output to
# build/asan/logs/READER.log.
set -euo pipefail
cd "$(dirname "$0")/.."

readers=(carmen carmen_gz relations isam landmark_csv scenario floor_plan waypoints
         occupancy_image trajectory suite_manifest mrclam pose_graph)
usage() { echo "usage: scripts/fuzz.sh READER|all SECONDS (READER: ${readers[*]})" >&2; exit 2; }
[ $# -eq 2 ] || usage
[[ $2 =~ ^[1-9][0-9]*$ ]] || usage
build=build/asan

run() {
  local reader=$1 seconds=$2
  local fuzzer=$build/bin/${reader}_fuzzer
  if [ ! -d "fuzz/corpus/$reader" ]; then usage; fi
  if [ ! -x "$fuzzer" ]; then
    echo "fuzz: $fuzzer is missing: run scripts/setup.sh asan first" >&2
    return 2
  fi
  local work=$build/corpus-work/$reader artifacts=$build/artifacts/$reader
  local log=$build/logs/$reader.log
  mkdir -p "$work" "$artifacts" "$build/logs"
  cp fuzz/corpus/"$reader"/* "$work"/
  local options=(-timeout=2 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_total_time="$seconds"
                 -print_final_stats=1 -artifact_prefix="$artifacts/")
  [ -f "fuzz/dict/$reader.dict" ] && options+=(-dict="fuzz/dict/$reader.dict")
  # yaml-cpp and libstdc++ are built without frame pointers, so ASan's fast unwinder reads
  # garbage frames through them and keeps nearly every allocation's "stack" as a new one: the
  # YAML readers' harnesses had 3.2 million of them (233 MB) after 40 s, growing until the 2 GB
  # limit ends a 10-minute campaign. The YAML readers' harnesses record no allocation stacks (error reports still
  # show where the error is; rerun the artifact without this option for the allocation's stack);
  # the exact unwinder (fast_unwind_on_malloc=0) ran them 16 times slower.
  local asan_options=${ASAN_OPTIONS:-}
  case "$reader" in
    scenario | occupancy_image | suite_manifest)
      asan_options=${asan_options:+$asan_options:}malloc_context_size=1 ;;
  esac
  local status=0
  # UBSan aborts on its first report in this build (-fno-sanitize-recover=all); the stack trace
  # says where.
  ASAN_OPTIONS=$asan_options UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$fuzzer" "${options[@]}" "$work" >"$log" 2>&1 || status=$?
  local executed speed rss
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log" | tail -1)
  if [ "$status" -ne 0 ]; then
    echo "fuzz: $reader: FAILED (exit $status) after ${executed:-?} inputs, log $log" >&2
    grep -E "^(==[0-9]+== ?ERROR|SUMMARY|terminate called|  what\(\)|.*runtime error|slamkit fuzz:|artifact_prefix)" \
      "$log" | head -20 >&2 || true
    return 1
  fi
  echo "fuzz: $reader: ${executed:-?} inputs in ${seconds} s (${speed:-?}/s, peak RSS ${rss:-?} MB): OK"
}

if [ "$1" = all ]; then
  failed=()
  for reader in "${readers[@]}"; do run "$reader" "$2" || failed+=("$reader"); done
  if [ ${#failed[@]} -gt 0 ]; then
    echo "fuzz: findings in ${failed[*]}" >&2
    exit 1
  fi
else
  run "$1" "$2"
fi
