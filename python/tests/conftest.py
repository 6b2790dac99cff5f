"""Shared fixtures: the bundled data (INTGRID_DATA_DIR, else the source tree's data/)."""
import os
import pathlib

import pytest

import intgrid

DATA_DIR = pathlib.Path(
    os.environ.get("INTGRID_DATA_DIR", pathlib.Path(__file__).resolve().parents[2] / "data"))


@pytest.fixture(scope="session")
def data_dir():
    if not (DATA_DIR / "malaga_telecom_loop.log").exists():
        pytest.skip(f"bundled data not found in {DATA_DIR} (set INTGRID_DATA_DIR)")
    return DATA_DIR


@pytest.fixture(scope="session")
def reference_log(data_dir):
    return intgrid.io.read_log(data_dir / "malaga_telecom_loop_reference.log")


@pytest.fixture(scope="session")
def loop_log(data_dir):
    return intgrid.io.read_log(data_dir / "malaga_telecom_loop.log")
