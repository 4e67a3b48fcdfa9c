#!/usr/bin/env python3
"""Renders a particle frame computed with numpy — a ball of water falling into a
shallow pool — through a fluidcastd, and writes the image as a PNG.

    PYTHONPATH=python FLUIDCAST_LIBRARY=build/lib/libfluidcast.so \\
        python3 python/examples/render_numpy.py 127.0.0.1:7450 -o drop.png

The pool is a jittered grid of particles filling a 2 x 2 x 0.2 box on z = 0, the
ball a grid-filled sphere of radius 0.35 above it, falling (its velocity is
sent too, and with --color-by speed the falling ball stands out in another
colour). Positions are built as float32 and C-contiguous, so libfluidcast sends
them straight from the array without a copy.
"""

import argparse
import sys

import numpy as np

import fluidcast


def pool_and_drop(spacing, seed=7):
    """(positions (N, 3), velocity (N, 3), density (N,)), all float32."""
    rng = np.random.default_rng(seed)
    axis = np.arange(-1.0, 1.0, spacing)
    x, y, z = np.meshgrid(axis, axis, np.arange(0.0, 0.2, spacing), indexing="ij")
    pool = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    pool += rng.uniform(-0.1, 0.1, pool.shape) * spacing   # not a perfect lattice

    ball_axis = np.arange(-0.35, 0.35 + 1e-9, spacing)
    bx, by, bz = np.meshgrid(ball_axis, ball_axis, ball_axis, indexing="ij")
    ball = np.stack([bx.ravel(), by.ravel(), bz.ravel()], axis=1)
    ball = ball[np.linalg.norm(ball, axis=1) <= 0.35] + (0.0, 0.0, 0.75)

    positions = np.concatenate([pool, ball]).astype(np.float32)
    velocity = np.zeros_like(positions)
    velocity[len(pool):, 2] = -2.0                          # the ball falls
    density = np.full(len(positions), 1000.0, np.float32)
    return positions, velocity, density


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("address", help="the daemon, HOST:PORT (or unix:PATH)")
    parser.add_argument("-o", "--output", default="drop.png", help="PNG to write (default drop.png)")
    parser.add_argument("--size", default="1280x720", help="image size WxH (default 1280x720)")
    parser.add_argument("--spacing", type=float, default=0.03, help="particle spacing (default 0.03)")
    parser.add_argument("--color-by", default="none", choices=["none", "speed", "density"],
                        help="tint the fluid by an attribute (default none)")
    parser.add_argument("--token", help="the daemon's token, if it wants one")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))

    positions, velocity, density = pool_and_drop(args.spacing)
    try:
        with fluidcast.connect(args.address, token=args.token, name="render_numpy.py") as client:
            client.send_frame(positions, velocity=velocity, density=density)
            client.set_camera(eye=(2.0, -2.9, 1.9), target=(0.0, 0.0, 0.3), up=(0, 0, 1), fov=40,
                              size=(width, height))
            settings = dict(radius=0.9 * args.spacing)
            if args.color_by != "none":
                settings.update(color_by=args.color_by, colormap="turbo",
                                color_range=(0.0, 2.0) if args.color_by == "speed" else (900.0, 1100.0))
            client.set_settings(**settings)
            image = client.render_result(format="png")
    except fluidcast.Error as e:
        print("render_numpy.py: %s" % e, file=sys.stderr)
        return 1
    with open(args.output, "wb") as f:
        f.write(image.data)
    print("render_numpy.py: %d particles -> %s (%dx%d, %.0f ms on the server)"
          % (len(positions), args.output, image.width, image.height,
             image.stage_ms.get(fluidcast.Stage.TOTAL, float("nan"))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
