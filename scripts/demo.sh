#!/usr/bin/env bash
# Sets everything up, then runs the default demo: EKF-SLAM on a simulated car-like robot
# (configs/default.yaml, 20 Monte Carlo runs). Results and figures go to out/demo/. Builds only
# the `slamkit` program (scripts/test.sh builds the rest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release slamkit
build/release/bin/slamkit demo --out out/demo "$@"
