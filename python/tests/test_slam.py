"""SLAM scan by scan from Python against run_grid_slam over a whole log: the bundled real log's first
60 scans (12 m of the loop, 3 s a run; tests/pipeline/slam_data_test.cpp runs all 225)."""
import math

import numpy as np
import pytest

import intgrid


def copy_scan(scan):
    """The scan rebuilt field by field in Python, so that GridSlam sees what Python hands it."""
    return intgrid.Scan(t=scan.t, robot=intgrid.Pose2(*scan.robot.as_tuple()),
                        sensor_mount=intgrid.Pose2(*scan.sensor_mount.as_tuple()),
                        angle0=scan.angle0, dangle=scan.dangle, max_range=scan.max_range,
                        ranges=list(scan.ranges))


SCANS = 60


@pytest.fixture(scope="module")
def prefix_log(loop_log):
    scans = loop_log.scans[:SCANS]
    return intgrid.Log(scans, [o for o in loop_log.odometry if o.t <= scans[-1].t])


@pytest.fixture(scope="module")
def both_runs(prefix_log):
    config = intgrid.GridSlamConfig()
    run = intgrid.run_grid_slam(prefix_log, config, "int")
    scans = prefix_log.scans
    slam = intgrid.GridSlam(config, intgrid.Arithmetic.integer, scans[0],
                            intgrid.odometry_reach(scans))
    poses, sigmas = [], []
    for scan in scans:
        slam.insert(copy_scan(scan))
        p = slam.pose()
        poses.append((scan.t, p.x, p.y, p.theta))
        sigmas.append(slam.sigma())
    return run, slam, np.array(poses), np.array(sigmas)


def test_scan_by_scan_gives_run_grid_slams_trajectory_and_map_bit_for_bit(both_runs):
    run, slam, poses, sigmas = both_runs
    assert run.scans == slam.scans == SCANS
    np.testing.assert_array_equal(poses, run.trajectory)  # every pose, exactly
    np.testing.assert_array_equal(sigmas, run.sigma)
    final = slam.pose()
    assert (final.x, final.y, final.theta) == tuple(run.trajectory[-1, 1:])
    (ours, geometry), (theirs, run_geometry) = slam.map(), run.map
    assert geometry == run_geometry and ours.dtype == np.int8
    np.testing.assert_array_equal(ours, theirs)
    assert (slam.localizations, slam.mappings) == (run.localizations, run.mappings)
    assert slam.readings == run.readings == SCANS * 361


def test_the_run_moved_and_beats_odometry_against_the_reference(both_runs, prefix_log,
                                                                 reference_log):
    run, slam, poses, _ = both_runs
    path = np.hypot(np.diff(poses[:, 1]), np.diff(poses[:, 2])).sum()
    assert path > 10.0  # measured 12.5 m
    assert np.hypot(*(poses[-1, 1:3] - poses[0, 1:3])) > 5.0
    # Against the reference poses of the same times (13 of them): measured 0.17 m for the SLAM,
    # 0.64 m for raw odometry.
    ate = intgrid.absolute_trajectory_error(run.trajectory, reference_log)
    odometry = intgrid.absolute_trajectory_error(intgrid.scan_poses(prefix_log), reference_log)
    assert ate.matched == odometry.matched == 13
    assert ate.rmse <= 0.25 and odometry.rmse > 2 * ate.rmse
    # The map: walls, and much more empty than occupied.
    cells, _ = run.map
    assert (cells > 0).sum() > 500 and (cells < 0).sum() > 10 * (cells > 0).sum()
    probabilities, geometry = slam.map_probabilities()
    assert probabilities.shape == geometry.shape
    np.testing.assert_array_equal(probabilities, run.map_probabilities()[0])


def test_nested_config_reads_and_writes_and_checks():
    config = intgrid.GridSlamConfig(cell=0.05)
    assert config.cell == 0.05 and config.headings == 1024
    config.sensor.sigma = 0.03
    config.schedule.lambda_ = 2
    config.window.cells = 13
    config.map.margin = 5.0
    config.ugamma.bits = 20
    config.motion.theta0 = 0.004
    assert (config.sensor.sigma, config.schedule.lambda_, config.window.cells, config.map.margin,
            config.ugamma.bits, config.motion.theta0) == (0.03, 2, 13, 5.0, 20, 0.004)
    config.beam = intgrid.GridSlamConfig.BeamModel(tempering=4)
    assert config.beam.tempering == 4 and config.sensor.sigma == 0.03  # the other groups stay
    assert "window=" in repr(config)
    config.check()
    config.window.cells = 12
    with pytest.raises(ValueError, match="window.cells"):
        config.check()
    with pytest.raises(TypeError, match="no field 'lamda'"):
        intgrid.GridSlamConfig.Schedule(lamda=3)


def test_slam_errors_are_value_errors(loop_log):
    scans = loop_log.scans
    config = intgrid.GridSlamConfig()
    config.window.cells = 12
    with pytest.raises(ValueError, match="window.cells"):
        intgrid.GridSlam(config, "int", scans[0], 10.0)
    with pytest.raises(ValueError, match="arithmetic must be"):
        intgrid.GridSlam(intgrid.GridSlamConfig(), "fixed", scans[0], 10.0)
    slam = intgrid.GridSlam(intgrid.GridSlamConfig(), "float", scans[0], 10.0)
    other = copy_scan(scans[1])
    other.ranges = other.ranges[:100]
    with pytest.raises(ValueError, match="beam count"):
        slam.insert(other)
    with pytest.raises(ValueError, match="no scans"):
        intgrid.run_grid_slam(intgrid.Log())
