#!/usr/bin/env python3
"""Writes deploy/demo/drop_64k.f32, the quick start's scene: a sphere of water
(radius 0.3, centre 0.6 above the floor) above a shallow pool (2.0 x 2.0 x 0.12)
on the floor z = 0, 65,536 particles as raw little-endian float32 x, y, z.

Laid out the way a solver's initial state is, so the demo shows the renderer
and not the generator's artefacts: the pool is a full cubic lattice (a flat
top, no missing points), the sphere concentric shells of evenly spread points
(Fibonacci spirals), so its surface is a sphere and not a lattice's staircase.
The spacing is the one whose scene comes nearest 65,536 points; the shells'
sizes are then scaled by the small remaining factor, so the sphere stays solid
and its points as evenly spread.

    python3 deploy/demo/make_drop.py [OUTPUT]
"""
import math
import struct
import sys

COUNT = 65536
POOL_HALF, POOL_DEPTH = 1.0, 0.12
DROP_RADIUS, DROP_Z = 0.3, 0.6
GOLDEN_ANGLE = math.pi * (3.0 - math.sqrt(5.0))


def pool(h):
    n_xy = int(round(2.0 * POOL_HALF / h))
    n_z = max(int(round(POOL_DEPTH / h)), 1)
    step_xy = 2.0 * POOL_HALF / n_xy
    step_z = POOL_DEPTH / n_z
    return [(-POOL_HALF + (i + 0.5) * step_xy, -POOL_HALF + (j + 0.5) * step_xy, (k + 0.5) * step_z)
            for k in range(n_z) for j in range(n_xy) for i in range(n_xy)]


def shell_sizes(h):
    """Points on each shell, outermost first: about its area over h squared."""
    sizes, r = [], DROP_RADIUS - 0.5 * h
    while r > 0.25 * h:
        sizes.append(max(int(round(4.0 * math.pi * r * r / (h * h))), 1))
        r -= h
    return sizes


def shell(radius, n):
    points = []
    for i in range(n):
        z = 1.0 - 2.0 * (i + 0.5) / n
        ring = math.sqrt(max(1.0 - z * z, 0.0))
        a = GOLDEN_ANGLE * i
        points.append((radius * ring * math.cos(a), radius * ring * math.sin(a), DROP_Z + radius * z))
    return points


def total(h):
    return len(pool(h)) + sum(shell_sizes(h))


def spacing():
    """The spacing, within 10 % of the volume's, whose scene comes nearest COUNT
    points (the pool's lattice makes the count jump as the spacing changes)."""
    h0 = (((2 * POOL_HALF) ** 2 * POOL_DEPTH + 4.0 / 3.0 * math.pi * DROP_RADIUS ** 3) / COUNT) ** (1.0 / 3.0)
    candidates = [h0 * (0.9 + 0.2 * i / 2000) for i in range(2001)]
    return min(candidates, key=lambda h: abs(total(h) - COUNT))


def fit_shells(sizes, count):
    """The shells' sizes scaled to add up to `count`, the rounding's remainder
    on the outermost shell."""
    scale = count / sum(sizes)
    fitted = [max(int(round(n * scale)), 1) for n in sizes]
    fitted[0] += count - sum(fitted)
    return fitted


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "deploy/demo/drop_64k.f32"
    h = spacing()
    points = pool(h)
    sizes = fit_shells(shell_sizes(h), COUNT - len(points))
    for k, n in enumerate(sizes):
        points += shell(DROP_RADIUS - (k + 0.5) * h, n)
    assert len(points) == COUNT
    with open(out, "wb") as f:
        f.write(b"".join(struct.pack("<3f", *p) for p in points))
    print(f"{out}: {COUNT} particles, spacing {h:.5f}, {len(sizes)} shells of {sizes[0]} to {sizes[-1]} points")


if __name__ == "__main__":
    main()
