#!/usr/bin/env bash
# Issue 31 part 5 against a real Slurm: starts munged, slurmctld and slurmd on 127.0.0.1 (one
# node, a configuration in a temporary folder, nothing installed system-wide beyond the Debian
# packages slurm-wlm and munge), submits a 4-shard `slamkit mc` study with
# scripts/slurm/submit.sh, waits for the merge job, checks that the merged metrics.json equals an
# unsharded run's (step times aside), and stops the daemons. Needs root (slurmd) and the Release
# program (scripts/setup.sh release slamkit). Not part of scripts/test.sh: it starts system
# daemons; run it on its own: scripts/slurm/test_slurm.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
missing=()
for package in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "ok installed" || missing+=("$package")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  apt-get install -y --no-install-recommends "${missing[@]}" >/dev/null
fi
program=build/release/bin/slamkit
[[ -x $program ]] || scripts/setup.sh release slamkit
work=$(mktemp -d /tmp/slamkit_slurm.XXXXXX)
conf=$work/slurm.conf
cpus=$(nproc)
mkdir -p "$work/state" "$work/spool"
cat >"$conf" <<CONF
ClusterName=slamkit-test
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=slamkit-node NodeHostname=$(hostname -s) NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$conf
stop() {  # the daemons this script started, each waited for
  local pids=()
  for file in "$work/slurmd.pid" "$work/slurmctld.pid"; do
    [[ -f $file ]] && pids+=("$(cat "$file")")
  done
  [[ -n ${munge_started:-} && -f /run/munge/munged.pid ]] && pids+=("$(cat /run/munge/munged.pid)")
  [[ ${#pids[@]} -gt 0 ]] || return 0
  kill "${pids[@]}" 2>/dev/null || true
  for _ in $(seq 1 50); do
    kill -0 "${pids[@]}" 2>/dev/null || return 0
    sleep 0.2
  done
  kill -9 "${pids[@]}" 2>/dev/null || true
}
trap stop EXIT
if ! munge -n </dev/null >/dev/null 2>&1; then
  mkdir -p /run/munge && chown munge:munge /run/munge
  runuser -u munge -- /usr/sbin/munged
  munge_started=1
fi
/usr/sbin/slurmctld -f "$conf"
/usr/sbin/slurmd -f "$conf" -N slamkit-node
for _ in $(seq 1 60); do
  sinfo -h -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)' && break
  sleep 1
done
sinfo
args=(mc --config configs/short.yaml --runs 12 --no-figures)
echo "unsharded: $program ${args[*]}"
"$program" "${args[@]}" --out "$work/whole" >/dev/null
echo "sharded:   scripts/slurm/submit.sh --shards 4 --out $work/sharded -- ${args[*]}"
scripts/slurm/submit.sh --shards 4 --out "$work/sharded" -- "${args[@]}"
for _ in $(seq 1 300); do
  [[ -z $(squeue -h 2>/dev/null) ]] && break
  sleep 1
done
squeue
cat "$work/sharded/logs/merge.log"
python3 - "$work/whole/metrics.json" "$work/sharded/merged/metrics.json" <<'PY'
import json, sys
def load(path):
    m = json.load(open(path))
    for key in ("step_time_mean_s", "step_time_max_s"):
        m.pop(key, None)
    for run in m["per_run"]:
        run.pop("step_time_mean_s", None)
        run.pop("step_time_max_s", None)
    return m
whole, merged = load(sys.argv[1]), load(sys.argv[2])
if whole != merged:
    print("test_slurm: the merged metrics.json differs from the unsharded run's:",
          [k for k in whole if whole.get(k) != merged.get(k)])
    sys.exit(1)
print(f"test_slurm: 4 shards on Slurm merged equal the unsharded run: {whole['runs']} runs, "
      f"position RMSE {whole['position_rmse_m']:.6f} m, ANEES {whole['anees']:.6f}")
PY
