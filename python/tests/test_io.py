"""Reading and writing logs and ROS maps; bad input is intgrid.io.InputError (a ValueError)."""
import numpy as np
import pytest

import intgrid
from intgrid.io import InputError, read_log, read_ros_map, write_log, write_ros_map


def test_bundled_logs(reference_log, loop_log):
    assert len(reference_log.scans) == 99 and len(loop_log.scans) == 225
    scan = reference_log.scans[0]
    assert scan.ranges.shape == (361,) and scan.ranges.dtype == np.float64
    assert scan.dangle == pytest.approx(np.pi / 360, rel=1e-4)  # 361 beams over 180 degrees
    # The same scans, same timestamps (data/README.md).
    loop_times = {s.t for s in loop_log.scans}
    assert all(s.t in loop_times for s in reference_log.scans)


def test_write_log_reads_back_bit_for_bit(reference_log, tmp_path):
    log = intgrid.Log(reference_log.scans[:3],
                      [intgrid.OdometryRecord(reference_log.scans[0].t, intgrid.Pose2(1, 2, 3))])
    write_log(tmp_path / "out.log", log)
    back = read_log(tmp_path / "out.log")
    assert len(back.scans) == 3 and len(back.odometry) == 1
    for a, b in zip(log.scans, back.scans):
        np.testing.assert_array_equal(a.ranges, b.ranges)
        assert (a.t, a.robot.as_tuple(), a.sensor_mount.as_tuple()) == \
            (b.t, b.robot.as_tuple(), b.sensor_mount.as_tuple())
    assert back.odometry[0].pose.as_tuple() == (1.0, 2.0, 3.0)


def test_bundled_map(data_dir):
    m = read_ros_map(data_dir / "malaga_telecom_map.yaml")
    g = m.geometry
    assert (g.width, g.height, g.resolution, g.origin_x, g.origin_y) == (1700, 1740, 0.05, -45, -51)
    assert (m.occupied_thresh, m.free_thresh) == (0.65, 0.196)
    assert m.cells.shape == (1740, 1700)
    finite = m.cells[np.isfinite(m.cells)]
    assert finite.min() >= 0.0 and finite.max() <= 1.0
    assert (finite > 0.65).sum() > 5000


def read_pgm(path):
    """A binary PGM (P5, maxval 255) read in plain Python: rows top first."""
    data = path.read_bytes()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P5" and fields[3] == b"255"
    width, height = int(fields[1]), int(fields[2])
    pixels = np.frombuffer(data[pos + 1:], np.uint8)
    assert pixels.size == width * height
    return pixels.reshape(height, width)


def test_write_ros_map_round_trip_and_row_order(tmp_path):
    geometry = intgrid.GridGeometry(7, 5, 0.1, -0.3, 2.0)
    rng = np.random.default_rng(1)
    cells = rng.uniform(0.0, 1.0, size=(5, 7))
    cells[0, :] = 1.0  # the bottom row occupied
    cells[4, :] = 0.0  # the top row free
    write_ros_map(tmp_path / "m.yaml", cells, geometry, occupied_thresh=0.7, free_thresh=0.2)
    back = read_ros_map(tmp_path / "m.yaml")
    assert back.geometry == geometry
    assert (back.occupied_thresh, back.free_thresh) == (0.7, 0.2)
    assert np.abs(back.cells - cells).max() <= 1.0 / 510 + 1e-12
    # The image's first row is the top of the map: free (white, 255); its last the bottom.
    pixels = read_pgm(tmp_path / "m.pgm")
    assert (pixels[0] == 255).all() and (pixels[-1] == 0).all()
    # The RosMap and ProbabilityGrid forms write the same files.
    write_ros_map(tmp_path / "n.yaml", intgrid.ProbabilityGrid(cells, geometry), 0.7, 0.2)
    assert (tmp_path / "n.pgm").read_bytes() == (tmp_path / "m.pgm").read_bytes()


def test_input_errors_name_file_line_and_field(tmp_path):
    with pytest.raises(InputError) as missing:
        read_log(tmp_path / "missing.log")
    assert isinstance(missing.value, ValueError)
    assert missing.value.file.endswith("missing.log") and missing.value.line == 0
    bad = tmp_path / "bad.log"
    bad.write_text("ODOM 0 0 0 1\nRLASER 2 0 0.1 10 1.0 zwei 0 0 0 0 0 0 2\n")
    with pytest.raises(ValueError) as parse:
        read_log(bad)
    assert parse.value.line == 2 and "bad.log:2" in str(parse.value)
    with pytest.raises(InputError):
        read_ros_map(tmp_path / "missing.yaml")


def test_grid_arrays_must_match_their_geometry():
    with pytest.raises(ValueError, match=r"shape \(height, width\) = \(5, 7\)"):
        intgrid.ProbabilityGrid(np.zeros((7, 5)), intgrid.GridGeometry(7, 5, 0.1))
    with pytest.raises(ValueError, match="resolution"):
        intgrid.ProbabilityGrid(np.zeros((5, 7)), intgrid.GridGeometry(7, 5, 0.0))
    with pytest.raises(ValueError, match="does not fit"):
        intgrid.IndexGrid(np.full((1, 2), 300), intgrid.GridGeometry(2, 1, 0.1))
    grid = intgrid.IndexGrid(np.array([[1, -2]]), intgrid.GridGeometry(2, 1, 0.1))
    assert grid.cells.dtype == np.int8 and grid.cells.tolist() == [[1, -2]]
