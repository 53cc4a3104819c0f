#!/usr/bin/env python3
"""SPEC S4's simulated experiments over seeds: `slamkit gridexplore` with prediction off (full
frontier coverage) and on (P-SLAM skips what it predicted), each seed its own robot noise and
filter seed; prints the exploration time, path, ATE and the maps against the truth per mode (as
they are, and laid onto the truth by `slamkit mapdiff --align`), and the hypotheses' similarity
with the finally built map. Standard library only.

usage: pslam_study.py SLAMKIT OUT_DIR [--plan maze|FILE --start x,y,th] [--seeds 1-10] [--jobs 2]
"""
import argparse
import concurrent.futures
import csv
import json
import os
import statistics
import subprocess


def run(slamkit, out, plan, start, seed, mode):
    d = os.path.join(out, f"{mode}-{seed}")
    cmd = [slamkit, "gridexplore", "--plan", plan, "--predict", mode, "--seed", str(seed),
           "--sim-seed", str(seed), "--out", d]
    if start:
        cmd += ["--start", start]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(d, "metrics.json")) as f:
        m = json.load(f)
    # The explored map laid onto the truth by the rigid motion that best matches their walls
    # (the filter's frame drifts as a whole; docs/pslam.md), at the one-cell tolerance.
    aligned = subprocess.run([slamkit, "mapdiff", os.path.join(d, "truth.yaml"),
                              os.path.join(d, "map.yaml"), "--json", "--tolerance", "1",
                              "--align"], check=True, capture_output=True, text=True).stdout
    m["aligned_vs_truth"] = json.loads(aligned)
    rows = []
    if mode == "on":
        with open(os.path.join(d, "hypotheses.csv")) as f:
            rows = list(csv.DictReader(f))
    return mode, seed, m, rows


def spread(values):
    sd = statistics.stdev(values) if len(values) > 1 else 0.0
    return f"{statistics.mean(values):.3f} ± {sd:.3f} [{min(values):.3f}, {max(values):.3f}]"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("slamkit")
    ap.add_argument("out")
    ap.add_argument("--plan", default="maze")
    ap.add_argument("--start", default="")
    ap.add_argument("--seeds", default="1-10")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--modes", default="off,on")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.seeds.split("-"))
    jobs = [(s, m) for s in range(lo, hi + 1) for m in a.modes.split(",")]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = [pool.submit(run, a.slamkit, a.out, a.plan, a.start, s, m) for s, m in jobs]
        for f in futures:
            mode, seed, m, rows = f.result()
            results.setdefault(mode, []).append((seed, m, rows))
    for mode, runs in sorted(results.items()):
        ms = [m for _, m, _ in runs]
        print(f"predict {mode}: {len(ms)} runs, finished {sum(m['finished'] for m in ms)}")
        for key in ("exploration_time_s", "path_length_m", "ate_rmse_m", "odometry_ate_rmse_m",
                    "closest_wall_m"):
            print(f"  {key:<28} {spread([m[key] for m in ms])}")
        for which in ("explored_vs_truth", "combined_vs_truth", "aligned_vs_truth"):
            for key in ("dice_occupied", "cell_accuracy"):
                print(f"  {which + '.' + key:<28} {spread([m[which][key] for m in ms])}")
        if mode == "on":
            covered = [m["explored_area_m2"] + m["predicted_area_m2"] for m in ms]
            share = [m["predicted_area_m2"] / c for m, c in zip(ms, covered)]
            print(f"  {'predicted share of covered':<28} {spread(share)}")
            rows = [r for _, _, rs in runs for r in rs]
            made = [r for r in rows if r["fate"] not in ("no_structure", "below_threshold")]
            sims = [float(r["final_similarity"]) for r in made if r["final_similarity"]]
            fates = {}
            for r in rows:
                fates[r["fate"]] = fates.get(r["fate"], 0) + 1
            print(f"  requests {len(rows)} ({len(rows) / len(ms):.1f} a run), fates {fates}")
            if sims:
                print(f"  hypotheses scored {len(sims)} ({len(sims) / len(ms):.1f} a run): "
                      f"final similarity {spread(sims)}, above 0.4: {sum(s > 0.4 for s in sims)}")


if __name__ == "__main__":
    main()
