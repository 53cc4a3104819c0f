#!/usr/bin/env bash
# Runs every example that a subcommand's --help ends with, as written, from the repository root
# (those marked "# after ..." last, since they read another example's output), and prints each
# one's exit code and wall time. tests/apps/help_examples_test.cpp checks them with --dry-run on
# every test run; this runs them for real (the whole suite example takes the longest).
# Usage: scripts/analysis/help_examples.sh [PROGRAM]   (default build/release/bin/slamkit)
set -uo pipefail
cd "$(dirname "$0")/../.."
program=${1:-build/release/bin/slamkit}
examples() {
  "$program" --help | awk '/^Subcommands:/{on=1; next} on && /^  [a-z]/{print $1}' |
    while read -r name; do
      "$program" "$name" --help | awk '/^Examples \(from the repository root\):/{on=1; next} on && /^  /{sub(/^  /, ""); print}'
    done
}
mapfile -t all < <(examples)
ordered=()
for line in "${all[@]}"; do [[ $line != *"# after"* ]] && ordered+=("$line"); done
for line in "${all[@]}"; do [[ $line == *"# after"* ]] && ordered+=("$line"); done
failed=0
for line in "${ordered[@]}"; do
  start=$EPOCHREALTIME
  bash -c "$line" >/tmp/slamkit_example.log 2>&1
  rc=$?
  seconds=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')
  printf '%7s s  rc %d  %s\n' "$seconds" "$rc" "$line"
  [[ $rc -eq 0 ]] || { failed=1; tail -5 /tmp/slamkit_example.log; }
done
exit $failed
