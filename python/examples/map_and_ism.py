#!/usr/bin/env python3
"""Build an occupancy map from the bundled real log and look at one beam's inverse sensor model.

    PYTHONPATH=build/full/python python3 python/examples/map_and_ism.py --out /tmp/intgrid-map

Writes OUT/map.yaml and OUT/map.pgm (a ROS map_server map; view the PGM in any image viewer).
"""
import argparse
import os
import pathlib

import numpy as np

import intgrid

DEFAULT_DATA = pathlib.Path(os.environ.get(
    "INTGRID_DATA_DIR", pathlib.Path(__file__).resolve().parents[2] / "data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=pathlib.Path, default=DEFAULT_DATA)
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("intgrid-map"))
    parser.add_argument("--cell", type=float, default=0.05, help="cell size (m)")
    args = parser.parse_args()

    # One reading of 2 m through 5 cm cells, sigma 5 cm: P(occupied) of cells 1..50 along the beam.
    model = intgrid.GaussianBeamModel(sigma0=0.05)
    ism = intgrid.narrow_ism(model, z=2.0, cell=args.cell, cells=50)
    peak = int(np.argmax(ism))
    print(f"narrow ISM: cell {peak + 1} holds the maximum, P = {ism[peak]:.3f}; "
          f"cell 20 (1 m) P = {ism[19]:.2e}; cell 50 P = {ism[49]:.3f}")

    # The log's 99 scans with their reference poses, fused as 8-bit S_eps indices.
    log = intgrid.io.read_log(args.data / "malaga_telecom_loop_reference.log")
    grid, geometry = intgrid.map_from_scans(log, cell=args.cell, arithmetic="int")
    occupied = int((grid > 0.65).sum())
    free = int((grid < 0.196).sum())
    print(f"map: {geometry.width} x {geometry.height} cells of {geometry.resolution} m, "
          f"{occupied} occupied, {free} free, from {len(log.scans)} scans")

    # grid[iy, ix] is cell (ix, iy): row 0 is the bottom of the map. write_ros_map flips it into
    # the image's top-first rows.
    args.out.mkdir(parents=True, exist_ok=True)
    intgrid.io.write_ros_map(args.out / "map.yaml", grid, geometry)
    print(f"wrote {args.out / 'map.yaml'} and {args.out / 'map.pgm'}")


if __name__ == "__main__":
    main()
