#!/usr/bin/python3
"""check_compare_images.py OUT_DIR TAG - checks what bench/peer/compare_images.sh
wrote for one splash frame:

- compare_TAG.png is 2W wide and H plus a caption strip high, VTK's image
  (vtk_TAG.png) on the left and fluidcast's (fc_TAG.png) on the right, below
  the strip, pixel for pixel;
- each half differs from floor.png over most of the pool: the fluid is drawn
  where the particles project (computed here from scene.json's camera, not
  taken from either renderer), whatever the shading;
- each half equals floor.png in the image corners, far from any particle:
  both renderers show the same background, so the hand-over of floor.png to
  fluidcast (--background) works.
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "peer"))
import vtk_scene  # noqa: E402

DIFF = 8           # a channel differs by more than this: the pixel shows something else
CORNER = 16        # corner blocks, pixels per side
CORNER_TOL = 2     # per channel, in the corners (rounding of a colour-space round trip)
POOL_Z = 0.1       # splash pool particles below the surface (it is at about 0.14)
POOL_COVERED = 0.5  # at least this fraction of the pool's pixels must differ


def project(xyz, scene):
    """Pixel centres (x right, y down) and sphere radii in pixels of the
    points, for scene.json's look-at camera with a vertical field of view."""
    width, height = scene["size"]
    eye, target, up = (np.array(scene[k], dtype=np.float64) for k in ("eye", "target", "up"))
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    d = xyz.astype(np.float64) - eye
    z, x, y = d @ forward, d @ right, d @ true_up
    if np.any(z <= 0):
        raise SystemExit("FAIL: particles behind the camera; the check assumes the splash camera")
    focal = 1 / math.tan(math.radians(scene["fov"]) / 2)
    px = (x * focal / (z * width / height) + 1) / 2 * width
    py = (1 - y * focal / z) / 2 * height
    return px, py, scene["radius"] * focal / z * height / 2


def footprint(xyz, scene, grow=0.0):
    """Pixels whose centre lies in a projected sphere (radius + grow pixels)."""
    width, height = scene["size"]
    mask = np.zeros((height, width), bool)
    for cx, cy, r in zip(*project(xyz, scene)):
        r += grow
        x0, x1 = max(0, int(cx - r)), min(width, int(cx + r) + 2)
        y0, y1 = max(0, int(cy - r)), min(height, int(cy + r) + 2)
        if x0 >= x1 or y0 >= y1:
            continue
        yy, xx = np.mgrid[y0:y1, x0:x1]
        mask[y0:y1, x0:x1] |= (xx + 0.5 - cx) ** 2 + (yy + 0.5 - cy) ** 2 <= r * r
    return mask


def erode(mask, steps):
    for _ in range(steps):
        m = mask.copy()
        m[1:] &= mask[:-1]
        m[:-1] &= mask[1:]
        m[:, 1:] &= mask[:, :-1]
        m[:, :-1] &= mask[:, 1:]
        mask = m
    return mask


def main():
    out, tag = sys.argv[1], sys.argv[2]
    failures = []

    def check(ok, message):
        print(("ok:   " if ok else "FAIL: ") + message)
        if not ok:
            failures.append(message)

    with open(os.path.join(out, "scene.json")) as f:
        scene = json.load(f)
    width, height = scene["size"]
    floor = vtk_scene.read_png(os.path.join(out, "floor.png")).astype(np.int16)
    vtk = vtk_scene.read_png(os.path.join(out, f"vtk_{tag}.png")).astype(np.int16)
    fc = vtk_scene.read_png(os.path.join(out, f"fc_{tag}.png")).astype(np.int16)
    both = vtk_scene.read_png(os.path.join(out, f"compare_{tag}.png")).astype(np.int16)
    for name, image in (("floor.png", floor), (f"vtk_{tag}.png", vtk), (f"fc_{tag}.png", fc)):
        check(image.shape == (height, width, 3), f"{name} is {image.shape[1]}x{image.shape[0]}, expected {width}x{height}")
    if failures:
        return 1
    strip = both.shape[0] - height
    check(both.shape[1] == 2 * width, f"compare_{tag}.png is {both.shape[1]} wide, expected 2x{width}")
    check(0 < strip <= height // 5, f"compare_{tag}.png has a caption strip of {strip} rows above the images")
    if failures:
        return 1
    check(np.array_equal(both[strip:, :width], vtk), "left half is vtk image")
    check(np.array_equal(both[strip:, width:], fc), "right half is fluidcast image")
    check(np.ptp(both[:strip]) > 64, "caption strip has text (contrast)")

    frame = next(f for f in scene["frames"] if f["tag"] == tag)
    xyz = vtk_scene.read_particles(frame["path"])
    pool = erode(footprint(xyz[xyz[:, 2] < POOL_Z], scene), 2)
    check(pool.sum() > 0.05 * width * height, f"the pool covers {pool.sum()} pixels")
    near_fluid = footprint(xyz, scene, grow=8.0)
    for name, image in (("VTK", vtk), ("fluidcast", fc)):
        differs = np.abs(image - floor).max(axis=2) > DIFF
        share = differs[pool].mean()
        check(share >= POOL_COVERED, f"{name} differs from floor.png in {100 * share:.1f}% of the pool's pixels "
                                     f"(>= {100 * POOL_COVERED:.0f}%: the fluid is drawn)")
    c = CORNER
    for where, sl in (("top left", np.s_[:c, :c]), ("top right", np.s_[:c, -c:]),
                      ("bottom left", np.s_[-c:, :c]), ("bottom right", np.s_[-c:, -c:])):
        if near_fluid[sl].any():
            check(False, f"{where} corner is near a particle: the check's premise fails")
            continue
        for name, image in (("VTK", vtk), ("fluidcast", fc)):
            worst = int(np.abs(image[sl] - floor[sl]).max())
            check(worst <= CORNER_TOL, f"{name} {where} corner equals floor.png (max difference {worst})")
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
