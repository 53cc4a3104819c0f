#!/usr/bin/env bash
# Submits a sharded slamkit study to Slurm: a job array of N tasks, task K running
# `slamkit COMMAND ... --shard K/N --out OUT/shard_K`, and a job that runs once they all succeed,
# `slamkit merge OUT/shard_* --out OUT/merged`. Prints the two job ids.
#
#   scripts/slurm/submit.sh --shards 4 --out out/mc_sharded [--sbatch "--partition=cpu --time=1:00:00"] \
#       -- mc --config configs/default.yaml --runs 200
#
# COMMAND is one that takes --shard (mc). Run it from the repository root on a node that shares
# the file system with the compute nodes; SLAMKIT (default build/release/bin/slamkit) is the
# program each task runs. Each task's output and errors go to OUT/logs/.
set -euo pipefail
usage() { sed -n '2,12p' "$0" >&2; exit 2; }
shards="" out="" sbatch_args=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --shards) shards=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --sbatch) sbatch_args=$2; shift 2 ;;
    --) shift; break ;;
    *) usage ;;
  esac
done
[[ $shards =~ ^[1-9][0-9]*$ && -n $out && $# -gt 0 ]] || usage
program=$(realpath "${SLAMKIT:-build/release/bin/slamkit}")
[[ -x $program ]] || { echo "submit.sh: no program at $program (build it, or set SLAMKIT)" >&2; exit 2; }
# The command must parse and name existing files before anything is queued.
"$program" --dry-run "$@" --shard "1/$shards" --out "$out/shard_1" >/dev/null
mkdir -p "$out/logs"
out=$(realpath "$out")
quoted=$(printf ' %q' "$@")
# shellcheck disable=SC2086  # sbatch_args is a list of sbatch options
array=$(sbatch --parsable $sbatch_args --job-name=slamkit-shards --array="1-$shards" \
  --chdir="$PWD" --output="$out/logs/shard_%a.log" \
  --wrap="$(printf '%q' "$program")$quoted --shard \$SLURM_ARRAY_TASK_ID/$shards --out $(printf '%q' "$out")/shard_\$SLURM_ARRAY_TASK_ID")
array=${array%%;*}
shard_dirs=$(for k in $(seq 1 "$shards"); do printf ' %q' "$out/shard_$k"; done)
# shellcheck disable=SC2086
merge=$(sbatch --parsable $sbatch_args --job-name=slamkit-merge --dependency="afterok:$array" \
  --chdir="$PWD" --output="$out/logs/merge.log" \
  --wrap="$(printf '%q' "$program") merge$shard_dirs --out $(printf '%q' "$out")/merged")
echo "shards: job array $array (tasks 1-$shards); merge: job ${merge%%;*} -> $out/merged"
