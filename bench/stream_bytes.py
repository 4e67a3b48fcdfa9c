#!/usr/bin/python3
"""Bytes per frame of a session's viewers in JPEG and H.264 (PROTOCOL.md 10.7), same run, same frames.

A producer publishes every .ply of a directory (binary, x y z density vx vy vz as the splash frames are);
one viewer per format follows the session at WxH with the daemon's automatic camera, and each frame is
read by every viewer before the next is published, so none is skipped and the H.264 stream is the one a
viewer that keeps up receives. Prints bytes per frame for each format and their ratio.

    FLUIDCAST_LIBRARY=build/lib/libfluidcast.so python3 bench/stream_bytes.py HOST:PORT ../shared/data/splash \\
        [--size 1280x720] [--radius 0.0078571]

Needs python3-numpy and a running fluidcastd (start it with --refresh-ms 0: no PNG refresh in between).
"""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import fluidcast  # noqa: E402


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii", "replace").splitlines()
    n = int(next(line for line in header if line.startswith("element vertex")).split()[2])
    props = sum(1 for line in header if line.startswith("property float"))
    a = np.frombuffer(data, dtype="<f4", count=n * props, offset=end).reshape(n, props)
    return np.ascontiguousarray(a[:, :3])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("server")
    parser.add_argument("frames", help="directory of .ply frames")
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--radius", type=float, default=0.0078571)
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    producer = fluidcast.connect(args.server, reply_timeout=600)
    producer.publish("stream-bytes")
    viewers = {}
    for fmt in ("jpeg", "h264"):
        v = fluidcast.connect(args.server, reply_timeout=600)
        v.subscribe("stream-bytes", format=fmt, size=(width, height))
        v.set_settings(radius=args.radius)
        viewers[fmt] = v
    sizes = {fmt: [] for fmt in viewers}
    for path in sorted(glob.glob(os.path.join(args.frames, "*.ply"))):
        producer.send_frame(read_ply(path))
        for fmt, v in viewers.items():
            img = v.next_image()
            while img.refresh or img.view_change:
                img = v.next_image()
            sizes[fmt].append(len(img.data))
    producer.leave_session()
    for fmt, s in sizes.items():
        print("%-5s %2d frames, %8.0f bytes per frame (first %d, the others %.0f)"
              % (fmt, len(s), sum(s) / len(s), s[0], sum(s[1:]) / max(1, len(s) - 1)))
    print("H.264 / JPEG: %.3f" % (sum(sizes["h264"]) / sum(sizes["jpeg"])))


if __name__ == "__main__":
    main()
