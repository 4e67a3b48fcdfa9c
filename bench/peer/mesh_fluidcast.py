#!/usr/bin/env python3
"""The fluidcast side of mesh_vs_openvdb.sh: one .f32 frame meshed by a running
fluidcastd (Client.mesh, PROTOCOL.md section 13) at a cell of CELL particle
radii, written as binary PLY (x y z, triangles) for mesh_openvdb's distance.
One warm-up extraction, then the timed one: prints
"fluidcast: P particles, T triangles, S s (server extraction; W s with the transfer)".

usage: mesh_fluidcast.py ADDRESS IN.f32 RADIUS CELL OUT.ply"""
import sys
import time

import numpy as np

import fluidcast


def write_ply(path, positions, triangles):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\ncomment fluidcast\nelement vertex %d\n"
                 "property float x\nproperty float y\nproperty float z\nelement face %d\n"
                 "property list uchar uint vertex_indices\nend_header\n" % (len(positions), len(triangles))).encode())
        f.write(positions.astype("<f4").tobytes())
        faces = np.zeros(len(triangles), dtype=[("n", "u1"), ("i", "<u4", 3)])
        faces["n"], faces["i"] = 3, triangles
        f.write(faces.tobytes())


def main():
    address, path, radius, cell, out = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
    points = np.fromfile(path, dtype="<f4").reshape(-1, 3)
    with fluidcast.connect(address, reply_timeout=600) as client:
        client.send_frame(points)
        client.set_settings(radius=radius, surface_cell=cell)
        client.mesh(attributes=None)
        start = time.monotonic()
        mesh = client.mesh(attributes=None)
        wall = time.monotonic() - start
    write_ply(out, mesh.positions, mesh.triangles)
    print("fluidcast: %d particles, %d triangles, %.3f s (server extraction; %.3f s with the transfer)"
          % (len(points), len(mesh.triangles), mesh.extract_ms / 1000, wall))


if __name__ == "__main__":
    main()
