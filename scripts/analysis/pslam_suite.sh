#!/usr/bin/env bash
# P-SLAM on every log of the CARMEN suite (configs/carmen_suite.yaml), prediction off and on, for
# the seeds given: `slamkit grid` per log, its ATE (or relations for Intel) from metrics.json.
# usage: [DELAY=N] scripts/analysis/pslam_suite.sh SLAMKIT OUT_DIR [SEEDS...]   (default seed 1;
# DELAY: --prediction-delay-scans, default 0: the filter never waits, runs not bit-reproducible)
set -euo pipefail
slamkit=$1 out=$2
shift 2
seeds=("${@:-1}")
d=$(cd "$(dirname "$0")/../../../shared/datasets/carmen" && pwd)
runs=("intel|intel.clf|--relations $d/intel.relations"
      "freiburg-101|suite/freiburg-101.log.gz|--reference $d/suite/freiburg-101.reference.txt --pair-by time"
      "edmonton|suite/edmonton.log.gz|--reference $d/suite/edmonton.reference.txt --pair-by time"
      "belgioioso|suite/belgioioso.log.gz|--reference $d/suite/belgioioso.reference.txt --pair-by index"
      "acapulco|suite/acapulco.log.gz|--reference $d/suite/acapulco.reference.txt --pair-by time"
      "csail|suite/csail.log.gz|--reference $d/suite/csail.reference.txt --pair-by index"
      "freiburg-campus|suite/freiburg-campus.log.gz|--reference $d/suite/freiburg-campus.reference.txt --pair-by index")
echo "log,seed,predict,ate_rmse_m,relations_trans_mean_m,wall_time_s,hypotheses,active,explored,dropped,predicted_area_m2"
for run in "${runs[@]}"; do
  IFS='|' read -r name log scoring <<<"$run"
  for seed in "${seeds[@]}"; do
    for predict in off on; do
      dir=$out/$name/seed_$seed/$predict
      mkdir -p "$(dirname "$dir")"
      # shellcheck disable=SC2086
      "$slamkit" grid --log "$d/$log" $scoring --seed "$seed" --predict "$predict" \
        --prediction-delay-scans "${DELAY:-0}" --out "$dir" >"$dir.txt" 2>&1 || { echo "$name,$seed,$predict,failed"; continue; }
      python3 - "$dir/metrics.json" "$name" "$seed" "$predict" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
f = m.get("hypotheses_by_fate", {})
print(",".join(str(x) for x in [sys.argv[2], sys.argv[3], sys.argv[4], m.get("ate_rmse_m", ""),
      m.get("relations_trans_mean_m", ""), round(m["wall_time_s"], 1), m.get("hypotheses", 0),
      f.get("active", 0), f.get("explored", 0), f.get("dropped_by_recovery", 0),
      round(m.get("predicted_area_m2", 0.0), 1)]))
PY
    done
  done
done
