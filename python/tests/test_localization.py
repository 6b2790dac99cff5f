"""Global localization of one scan: real scans on the bundled map, and every method on a small
synthetic room whose scan is ray-cast here in numpy."""
import math

import numpy as np
import pytest

import intgrid


@pytest.fixture(scope="module")
def telecom(data_dir):
    ros_map = intgrid.io.read_ros_map(data_dir / "malaga_telecom_map.yaml")
    return intgrid.LocalizationMap(ros_map.grid, ros_map.occupied_thresh, ros_map.free_thresh,
                                   intgrid.GlobalLocConfig())


# Scans of the reference log the pose grid finds (docs/results.md: 95 of the 99 within
# 0.5 m and 15 degrees); their poses are the reference run's, which built the bundled map.
@pytest.mark.parametrize("index", [21, 70])
def test_real_scan_localizes_within_half_a_metre_and_15_degrees(telecom, reference_log, index):
    scan = reference_log.scans[index]
    estimate = intgrid.localize(telecom, scan, method="pog", beams=60)
    assert estimate.readings_used == 60
    error = math.hypot(estimate.robot.x - scan.robot.x, estimate.robot.y - scan.robot.y)
    heading = abs(intgrid.wrap_angle(estimate.robot.theta - scan.robot.theta))
    assert error <= 0.5, estimate
    assert heading <= math.radians(15), estimate
    # The robot estimate is the sensor's stepped back by the mount.
    sensor = intgrid.compose(estimate.robot, scan.sensor_mount)
    assert (sensor.x, sensor.y) == pytest.approx((estimate.sensor.x, estimate.sensor.y), abs=1e-9)


def room():
    """A 6 x 4 m room of 5 cm cells with a 1 x 0.5 m block in one corner (no symmetry)."""
    res = 0.05
    geometry = intgrid.GridGeometry(int(6.4 / res), int(4.4 / res), res, -0.2, -0.2)
    cells = np.zeros(geometry.shape)
    cells[:4, :] = cells[-4:, :] = cells[:, :4] = cells[:, -4:] = 1.0  # walls 20 cm thick
    x0, y0 = int((4.5 + 0.2) / res), int((2.8 + 0.2) / res)
    cells[y0:y0 + 10, x0:x0 + 20] = 1.0
    return cells, geometry


def ray_cast(cells, geometry, pose, bearings, step=0.002, limit=12.0):
    """Range to the first occupied cell along each bearing, by small steps."""
    d = np.arange(step, limit, step)
    angles = pose.theta + bearings
    x = pose.x + np.cos(angles)[:, None] * d
    y = pose.y + np.sin(angles)[:, None] * d
    ix = np.floor((x - geometry.origin_x) / geometry.resolution).astype(int)
    iy = np.floor((y - geometry.origin_y) / geometry.resolution).astype(int)
    hit = cells[iy.clip(0, geometry.height - 1), ix.clip(0, geometry.width - 1)] > 0.5
    return d[hit.argmax(axis=1)]


def scan_all_round(cells, geometry, truth, beams=90):
    """A noiseless scan of `beams` readings all round from the sensor pose `truth`."""
    angle0, dangle = -math.pi, 2 * math.pi / beams
    ranges = ray_cast(cells, geometry, truth, angle0 + dangle * np.arange(beams))
    return intgrid.Scan(robot=intgrid.Pose2(), angle0=angle0, dangle=dangle, max_range=20.0,
                        ranges=ranges)


@pytest.mark.parametrize("method", ["pog", "markov", "markov-mixture", "likelihood-field",
                                    intgrid.GlobalMethod.pose_grid])
def test_every_method_finds_the_pose_in_a_synthetic_room(method):
    cells, geometry = room()
    # On the lattice alone (no refinement): the estimate is then a cell of the scores returned.
    config = intgrid.GlobalLocConfig(pose_res=0.1, headings=32, refine_levels=0,
                                     sensor=intgrid.RangeSensor(max_range=10.0))
    lmap = intgrid.LocalizationMap(cells, geometry, 0.65, 0.196, config)
    truth = intgrid.Pose2(1.5, 1.2, 0.7)
    beams = 90
    scan = scan_all_round(cells, geometry, truth, beams)
    estimate, scores = intgrid.localize(lmap, scan, method=method, beams=0, return_scores=True)
    assert estimate.readings_used == beams
    assert math.hypot(estimate.robot.x - truth.x, estimate.robot.y - truth.y) <= 0.2
    assert abs(intgrid.wrap_angle(estimate.robot.theta - truth.theta)) <= 2 * lmap.heading_bin
    assert scores.shape == (lmap.headings, lmap.height, lmap.width)
    assert scores.max() == pytest.approx(estimate.score)
    if estimate.ties == 1:
        k, j, i = np.unravel_index(np.argmax(scores), scores.shape)
        best = lmap.pose_of(int(i), int(j), int(k))
        assert (best.x, best.y) == pytest.approx((estimate.sensor.x, estimate.sensor.y))


def test_refinement_places_the_pose_grid_estimate_between_the_lattice_cells():
    cells, geometry = room()
    truth = intgrid.Pose2(1.53, 1.17, 0.7)
    scan = scan_all_round(cells, geometry, truth)
    errors = []
    for levels in (0, 4):
        config = intgrid.GlobalLocConfig(pose_res=0.2, headings=32, refine_levels=levels,
                                         sensor=intgrid.RangeSensor(max_range=10.0))
        lmap = intgrid.LocalizationMap(cells, geometry, 0.65, 0.196, config)
        estimate = intgrid.localize(lmap, scan, method="pog", beams=0)
        errors.append(math.hypot(estimate.robot.x - truth.x, estimate.robot.y - truth.y))
    # The lattice's 0.2 m cells leave the truth up to a cell's half-diagonal (0.14 m) away;
    # refined on the map's 5 cm cells, a fraction of that.
    print("position error, lattice and refined:", errors)
    assert errors[1] <= 0.05
    assert errors[1] < errors[0]


def test_localization_errors_are_value_errors():
    cells, geometry = room()
    with pytest.raises(ValueError, match="free_threshold"):
        intgrid.LocalizationMap(cells, geometry, 0.5, 0.6, intgrid.GlobalLocConfig())
    with pytest.raises(ValueError, match="headings"):
        intgrid.LocalizationMap(cells, geometry, 0.65, 0.196, intgrid.GlobalLocConfig(headings=2))
    lmap = intgrid.LocalizationMap(cells, geometry, 0.65, 0.196,
                                   intgrid.GlobalLocConfig(pose_res=0.2, headings=8))
    scan = intgrid.Scan(dangle=0.1, max_range=10.0, ranges=[1.0, 2.0])
    with pytest.raises(ValueError, match="method must be"):
        intgrid.localize(lmap, scan, method="guess")
    with pytest.raises(IndexError):
        lmap.pose_of(lmap.width, 0, 0)
