#!/usr/bin/env python3
"""Each scan's turn from the scan before it, three ways: by the log's odometry, by a trajectory
(a SLAM run's trajectory.txt), and by aligning the two scans by brute force (no map, no prior).
A step where the trajectory follows the odometry but the scans say otherwise is where the front
end was held by its prior. FLASER logs (the Freiburg benchmark's); pure Python, slow: give a
stretch of a few seconds.

  scan_turns.py LOG.clf TRAJECTORY.txt T_FROM T_TO

Alignment: the later scan's endpoints turned by the odometry's turn +-20 degrees (0.5 degree
steps) and shifted by the odometry's translation +-0.16 m (4 cm steps); the score is the share of
its endpoints within a 5 cm cell of the earlier scan's (3 x 3 cells around each). Readings at
49 m or more are no returns.
"""
import math
import sys


def read_flaser(path):
    scans, odometry = {}, {}
    with open(path) as log:
        for line in log:
            f = line.split()
            if not f or f[0] != "FLASER":
                continue
            n = int(f[1])
            t = round(float(f[2 + n + 6]), 3)
            scans[t] = [float(r) for r in f[2 : 2 + n]]
            odometry[t] = tuple(map(float, f[2 + n + 3 : 2 + n + 6]))
    return scans, odometry


def endpoints(ranges):
    n = len(ranges)
    return [
        (r * math.cos(-math.pi / 2 + i * math.pi / n), r * math.sin(-math.pi / 2 + i * math.pi / n))
        for i, r in enumerate(ranges)
        if r < 49.0
    ]


def relative(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, math.atan2(math.sin(b[2] - a[2]), math.cos(b[2] - a[2]))


def aligned_turn(earlier, later, guess, cell=0.05):
    near = set()
    for x, y in endpoints(earlier):
        cx, cy = round(x / cell), round(y / cell)
        near.update((cx + i, cy + j) for i in (-1, 0, 1) for j in (-1, 0, 1))
    points = endpoints(later)
    best = (-1.0, guess[2])
    for k in range(-40, 41):
        turn = guess[2] + math.radians(0.5 * k)
        c, s = math.cos(turn), math.sin(turn)
        for i in range(-4, 5):
            for j in range(-4, 5):
                dx, dy = guess[0] + 0.04 * i, guess[1] + 0.04 * j
                hits = sum(
                    (round((c * x - s * y + dx) / cell), round((s * x + c * y + dy) / cell)) in near
                    for x, y in points
                )
                share = hits / max(1, len(points))
                if share > best[0]:
                    best = (share, turn)
    return best


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    scans, odometry = read_flaser(sys.argv[1])
    trajectory = {}
    with open(sys.argv[2]) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                v = line.split()
                trajectory[round(float(v[0]), 3)] = tuple(map(float, v[1:4]))
    t_from, t_to = float(sys.argv[3]), float(sys.argv[4])
    times = sorted(t for t in scans if t_from <= t <= t_to and t in trajectory)
    print("t (s)  turn from the scan before (degrees): odometry  trajectory  scans (their overlap)")
    for a, b in zip(times, times[1:]):
        guess = relative(odometry[a], odometry[b])
        share, turn = aligned_turn(scans[a], scans[b], guess)
        print(
            f"{b:.3f}  {math.degrees(guess[2]):6.1f}  {math.degrees(relative(trajectory[a], trajectory[b])[2]):6.1f}"
            f"  {math.degrees(turn):6.1f} ({share:.2f})"
        )


if __name__ == "__main__":
    main()
