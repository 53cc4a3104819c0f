#!/usr/bin/python3
"""EKF-SLAM on Victoria Park from Python, step by step, with the file's own noise.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/ekf_victoria_park.py

Prints the final pose with its standard deviations and the number of landmarks mapped. The
whole run as `slamkit run` does it, with its metrics, is slamkit.run_isam(path, config).
"""
import pathlib

import numpy as np

import slamkit

log_path = pathlib.Path("../shared/datasets/victoria_park/victoria_park_isam.txt")
log = slamkit.read_isam(log_path)
slam = slamkit.EkfSlam()  # or slamkit.EkfSlam("configs/victoria_park.yaml")
slam.reset()
z, covariances, _ = log.sightings(-1)
slam.update(z, covariances)
for step in range(len(log)):
    slam.predict(log.odometry[step], log.odometry_covariances[step])
    z, covariances, _ = log.sightings(step)
    slam.update(z, covariances)
sigma = np.sqrt(np.diag(slam.pose_covariance))
print(f"final pose: {slam.pose.round(3)} (sigma {sigma.round(3)}), "
      f"{slam.num_landmarks} landmarks")
