"""The Python module against the command line: the same figures from the same code."""
import json
import subprocess

import numpy as np
import pytest

import slamkit


def run_cli(cli, *args):
    result = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    return result


def test_the_isam_run_gives_the_command_line_figures(cli, datasets, root, tmp_path):
    log = datasets / "victoria_park" / "victoria_park_isam.txt"
    config = root / "configs" / "victoria_park.yaml"
    out = tmp_path / "vp"
    assert run_cli(cli, "run", "--isam", log, "--config", config, "--no-figures", "--out",
                   out).returncode == 0
    expected = json.loads((out / "metrics.json").read_text())
    metrics, estimate = slamkit.run_isam(log, config)
    for key in ("association_agreement", "association_agreement_merged", "landmarks_mapped",
                "sightings", "dropped", "smoothed_reference", "innovation_check",
                "odometry_heading_drift", "params"):
        assert metrics[key] == expected[key], key
    assert estimate.shape == (expected["poses"], 4)


def test_the_ekf_stepped_from_python_is_the_isam_run(datasets):
    """EkfSlam driven step by step from Python with the file's own noise: the path run_isam (and
    `slamkit run --isam` without --config) gives, pose for pose."""
    path = datasets / "victoria_park" / "victoria_park_isam.txt"
    log = slamkit.read_isam(path)
    _, expected = slamkit.run_isam(path)
    slam = slamkit.EkfSlam()
    slam.reset()
    z, covariances, _ = log.sightings(-1)
    slam.update(z, covariances)
    poses = [slam.pose]
    for step in range(len(log)):
        slam.predict(log.odometry[step], log.odometry_covariances[step])
        z, covariances, _ = log.sightings(step)
        slam.update(z, covariances)
        poses.append(slam.pose)
    assert np.array_equal(np.array(poses), expected[:, 1:])
    positions, landmark_covariances = slam.landmarks()
    assert positions.shape == (slam.num_landmarks, 2)
    assert landmark_covariances.shape == (slam.num_landmarks, 2, 2)
    assert slam.covariance.shape == (3 + 2 * slam.num_landmarks,) * 2


def test_the_grid_filter_on_3000_intel_scans_has_the_command_line_relations(cli, datasets,
                                                                            tmp_path):
    carmen = datasets / "carmen"
    out = tmp_path / "intel"
    result = run_cli(cli, "grid", "--log", carmen / "intel.clf", "--max-scans", 3000,
                     "--relations", carmen / "intel.relations", "--out", out)
    assert result.returncode == 0, result.stderr
    expected = json.loads((out / "metrics.json").read_text())
    log = slamkit.read_carmen(carmen / "intel.clf", max_scans=3000)
    slam = slamkit.GridSlam()
    for scan in (log[i] for i in range(len(log))):
        slam.process_scan(scan)
    slam.finish()
    trajectory = slam.trajectory()
    assert trajectory.shape == (3000, 4)
    relations = slamkit.evaluate_relations(trajectory, slamkit.read_relations(
        carmen / "intel.relations"), covered_only=True)
    assert relations["trans_mean_m"] == expected["relations_trans_mean_m"]
    assert relations["rot_mean_deg"] == expected["relations_rot_mean_deg"]
    grid = slam.map()
    assert grid["image"].dtype == np.uint8 and grid["resolution"] == 0.05
    assert (grid["image"] == 0).sum() > 1000  # walls


def test_scan_ranges_and_mrclam_odometry_are_views_not_copies(datasets):
    log = slamkit.read_carmen(datasets / "carmen" / "intel.clf", max_scans=10)
    scan = log[3]
    ranges = scan.ranges
    assert ranges.dtype == np.float32 and ranges.shape == (180,)
    assert not ranges.flags.owndata and not ranges.flags.writeable
    assert np.shares_memory(ranges, scan.ranges)  # both views of the scan's own buffer
    del log, scan  # the view keeps the data alive
    assert np.isfinite(ranges).all()
    robots, landmarks = slamkit.read_mrclam(datasets / "mrclam" / "MRCLAM_Dataset6")
    assert len(robots) == 5 and len(landmarks) == 15
    odometry = robots[0]["odometry"]
    assert odometry.shape[1] == 3 and not odometry.flags.owndata
    assert np.all(np.diff(odometry[:, 0]) >= 0)


def test_errors_are_python_exceptions_with_the_command_line_message(cli, tmp_path):
    bad = tmp_path / "bad.clf"
    bad.write_text("FLASER 3 1.0 2.0\n")
    with pytest.raises(slamkit.InputError) as error:
        slamkit.read_carmen(bad)
    result = run_cli(cli, "grid", "--log", bad, "--out", tmp_path / "out")
    assert result.returncode == 2
    assert f"slamkit: error: {error.value}" in result.stderr
    assert isinstance(error.value, ValueError)
    with pytest.raises(ValueError, match="trajectory is an"):
        slamkit.ate(np.zeros((3, 3)), np.zeros((3, 4)))


def test_nees_and_its_band():
    assert slamkit.nees(np.array([1.0, 0.0, 0.0]), np.eye(3)) == pytest.approx(1.0)
    lo, hi = slamkit.anees_band(50, 3)
    assert lo == pytest.approx(2.360, abs=5e-4) and hi == pytest.approx(3.716, abs=5e-4)
