#!/usr/bin/python3
"""The grid filter on the first 1,000 Intel scans from Python, scored on the relations metric.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/grid_intel.py

Each scan's ranges are a numpy view of the log read (no copy); the map comes back as
map_server's image with its resolution and origin.
"""
import pathlib

import slamkit

carmen = pathlib.Path("../shared/datasets/carmen")
log = slamkit.read_carmen(carmen / "intel.clf", max_scans=1000)
slam = slamkit.GridSlam()  # or slamkit.GridSlam("configs/grid.yaml")
for i in range(len(log)):
    slam.process_scan(log[i])
slam.finish()
relations = slamkit.evaluate_relations(slam.trajectory(),
                                       slamkit.read_relations(carmen / "intel.relations"),
                                       covered_only=True)
grid = slam.map()
print(f"final pose: {slam.pose.round(3)}; relations {relations['trans_mean_m']:.4f} m, "
      f"{relations['rot_mean_deg']:.3f} deg over {relations['count']}; "
      f"map {grid['image'].shape[1]} x {grid['image'].shape[0]} cells of {grid['resolution']} m")
