#!/usr/bin/python3
"""Writes a splash frame with two particle radii: the suggested 0.55 h0 for
x < 0.5 and twice that for x >= 0.5, as a binary PLY with a `radius` property
(what per-particle radii look like: make_gallery.sh renders it).

Usage: two_radii.py IN.ply OUT.ply"""
import sys

import numpy as np

RADIUS = 0.0078571

data = open(sys.argv[1], "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode()
names = [line.split()[-1] for line in header.splitlines() if line.startswith("property")]
count = int(next(line.split()[-1] for line in header.splitlines() if line.startswith("element vertex")))
values = np.frombuffer(data[end:end + 4 * len(names) * count], "<f4").reshape(count, len(names))
radius = np.where(values[:, names.index("x")] < 0.5, RADIUS, 2 * RADIUS).astype("<f4")
out = np.hstack([values, radius[:, None]]).astype("<f4")
header = header.replace("end_header\n", "property float radius\nend_header\n")
with open(sys.argv[2], "wb") as f:
    f.write(header.encode())
    f.write(out.tobytes())
