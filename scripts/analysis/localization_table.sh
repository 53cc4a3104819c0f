#!/usr/bin/env bash
# docs/localization.md's table: each CARMEN log mapped by `slamkit grid` (seed 1, defaults, one
# thread), then localised on that map from its first pose, both scored as the suite scores them.
# Usage: scripts/analysis/localization_table.sh OUT_DIR   (about 10 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:?usage: localization_table.sh OUT_DIR}
bin=build/release/bin/slamkit
data=../shared/datasets/carmen
mkdir -p "$out"
score() {  # metrics.json -> "relations m / deg" or "ATE m"
  python3 -c "import json,sys; m=json.load(open(sys.argv[1])); print('%.4f m / %.3f deg' % (m['relations_trans_mean_m'], m['relations_rot_mean_deg']) if 'relations_trans_mean_m' in m else 'ATE %.4f m' % m['ate_rmse_m'])" "$1"
}
run() {  # name, log, scoring options
  local name=$1 log=$2; shift 2
  "$bin" grid --log "$log" "$@" --threads 1 --out "$out/$name/grid" >/dev/null
  "$bin" localize --map "$out/$name/grid/map.yaml" --log "$log" "$@" --initial-pose 0,0,0 \
    --out "$out/$name/localize" >/dev/null
  echo "$name: localisation $(score "$out/$name/localize/metrics.json"), grid $(score "$out/$name/grid/metrics.json")"
}
run intel "$data/intel.clf" --relations "$data/intel.relations"
for entry in freiburg-101:time edmonton:time belgioioso:index acapulco:time csail:index \
             freiburg-campus:index; do
  name=${entry%%:*}
  run "$name" "$data/suite/$name.log.gz" --reference "$data/suite/$name.reference.txt" \
    --pair-by "${entry##*:}"
done
