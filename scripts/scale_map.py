#!/usr/bin/env python3
"""Scale a ROS map_server map (PGM + YAML) up to building size: every length times SCALE,
resampled (nearest cell) to cells of CELL metres. The globloc sweeps use it to try the localizer on
a real building's structure at campus size (docs/results.md, global localization).

    scripts/scale_map.py data/malaga_telecom_map.yaml 2.5 0.08 out/telecom_x2.5.yaml
"""
import os
import re
import sys


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        m = re.compile(rb"\s*(#[^\n]*\n\s*)*(\S+)").match(data, pos)
        if not m:
            sys.exit(f"{path}: header: not a binary PGM (P5)")
        fields.append(m.group(2))
        pos = m.end()
    if fields[0] != b"P5" or int(fields[3]) > 255:
        sys.exit(f"{path}: header: only 8-bit binary PGM (P5) is read")
    width, height = int(fields[1]), int(fields[2])
    pixels = data[pos + 1 : pos + 1 + width * height]
    if len(pixels) != width * height:
        sys.exit(f"{path}: pixels: {len(pixels)} bytes for {width} x {height}")
    return width, height, pixels


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    yaml_in, scale, cell, yaml_out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
    if not (scale > 0 and cell > 0):
        sys.exit("SCALE and CELL must be positive")
    text = open(yaml_in).read()
    field = lambda name: re.search(rf"^{name}:\s*(.+)$", text, re.M).group(1).strip()
    res = float(field("resolution"))
    origin = [float(v) for v in field("origin").strip("[]").split(",")]
    image = os.path.join(os.path.dirname(yaml_in), field("image"))
    width, height, pixels = read_pgm(image)
    step = cell / (res * scale)  # source pixels per output pixel
    out_w, out_h = int(width / step), int(height / step)
    if out_w * out_h > 2e8:
        sys.exit(f"{out_w} x {out_h} cells: too large")
    columns = [min(width - 1, int(u * step)) for u in range(out_w)]
    rows = bytearray()
    for v in range(out_h):
        start = min(height - 1, int(v * step)) * width
        src = pixels[start : start + width]
        rows += bytes(src[c] for c in columns)
    base = os.path.splitext(yaml_out)[0]
    os.makedirs(os.path.dirname(os.path.abspath(yaml_out)), exist_ok=True)
    with open(base + ".pgm.tmp", "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (out_w, out_h))
        f.write(rows)
    os.replace(base + ".pgm.tmp", base + ".pgm")
    body = re.sub(r"^image:.*$", f"image: {os.path.basename(base)}.pgm", text, flags=re.M)
    body = re.sub(r"^resolution:.*$", f"resolution: {cell}", body, flags=re.M)
    body = re.sub(r"^origin:.*$", f"origin: [{origin[0] * scale}, {origin[1] * scale}, {origin[2]}]",
                  body, flags=re.M)
    with open(yaml_out + ".tmp", "w") as f:
        f.write(body)
    os.replace(yaml_out + ".tmp", yaml_out)
    print(f"{yaml_out}: {out_w} x {out_h} cells of {cell} m, {out_w * cell:.1f} x {out_h * cell:.1f} m")


if __name__ == "__main__":
    main()
