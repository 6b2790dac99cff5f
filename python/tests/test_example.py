"""The README's example script runs and writes the map it says."""
import os
import pathlib
import subprocess
import sys

import numpy as np

import intgrid

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "map_and_ism.py"


def test_example_script_writes_the_map_of_map_from_scans(data_dir, reference_log, tmp_path):
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, str(EXAMPLE), "--data", str(data_dir), "--out",
                             str(out)], capture_output=True, text=True, env=os.environ.copy())
    assert result.returncode == 0, result.stderr
    assert "narrow ISM: cell 40 holds the maximum" in result.stdout
    assert "from 99 scans" in result.stdout
    written = intgrid.io.read_ros_map(out / "map.yaml")
    grid, geometry = intgrid.map_from_scans(reference_log)
    assert written.geometry == geometry
    assert np.abs(written.cells - grid).max() <= 1.0 / 510 + 1e-12
