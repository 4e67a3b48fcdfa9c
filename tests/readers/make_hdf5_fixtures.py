#!/usr/bin/env python3
"""Writes the HDF5 files test_reader_hdf5 reads, with h5py (Debian: python3-h5py), in
the layouts the SPH codes write: SWIFT/GADGET snapshots, PySPH output, H5Part, and
the broken ones the reader must refuse.

Usage: make_hdf5_fixtures.py DIR
Exits 77 (ctest's skip) without h5py. Particle i's values, the formulas the C test
checks: coordinate k = (3 i + k) * 0.25 - 1.5, velocity k = 0.5 i + k, density
1000 + i, smoothing length 0.01 (i + 1), id 7 i + 3."""
import os
import shutil
import sys

N = 100


def columns(np, dtype, n=N):
    i = np.arange(n, dtype=np.float64)
    pos = np.stack([(3 * i + k) * 0.25 - 1.5 for k in range(3)], axis=1).astype(dtype)
    vel = np.stack([0.5 * i + k for k in range(3)], axis=1).astype(dtype)
    return pos, vel, (1000 + i).astype(dtype), (0.01 * (i + 1)).astype(dtype), (7 * np.arange(n) + 3).astype(np.uint64)


def swift(h5py, np, path, dtype, optional, userblock=0):
    pos, vel, rho, h, ids = columns(np, dtype)
    kwargs = {"userblock_size": userblock} if userblock else {}
    with h5py.File(path, "w", **kwargs) as f:
        gas = f.create_group("PartType0")
        gas["Coordinates"] = pos
        if optional:
            header = f.create_group("Header")  # GADGET's header: optional to the reader
            header.attrs["NumPart_ThisFile"] = np.array([N, 0, 0, 0, 0, 0], dtype=np.uint32)
            header.attrs["BoxSize"] = 10.0
            gas["Velocities"] = vel
            gas["Density"] = rho
            gas["SmoothingLength"] = h
            gas["ParticleIDs"] = ids
            gas["Masses"] = np.full(N, 0.5, dtype=dtype)
            f.create_group("PartType1")["Coordinates"] = np.zeros((5, 3), dtype=dtype)  # dark matter: not read


def pysph(h5py, np, path, dtype, with_solid):
    """pysph/solver/output.py HDFOutput._dump: particles/<name>/arrays/<property>, one 1-D dataset each."""
    pos, vel, rho, h, ids = columns(np, dtype)
    with h5py.File(path, "w") as f:
        f.create_group("solver_data").attrs["t"] = 0.5
        arrays = f.create_group("particles").create_group("fluid").create_group("arrays")
        for k, name in enumerate("xyz"):
            arrays[name] = pos[:, k]
        for k, name in enumerate("uvw"):
            arrays[name] = vel[:, k]
        arrays["rho"] = rho
        arrays["h"] = h
        arrays["tag"] = np.zeros(N, dtype=np.int32)
        arrays["gid"] = np.arange(N, dtype=np.uint32)
        arrays["m"] = np.full(N, 0.25, dtype=dtype)
        if with_solid:  # a second particle array, without velocity, 100 along x: read after the fluid
            spos, _, srho, sh, _ = columns(np, dtype, 10)
            solid = f["particles"].create_group("solid").create_group("arrays")
            for k, name in enumerate("xyz"):
                solid[name] = spos[:, k] + (100 if k == 0 else 0)
            solid["rho"] = srho
            solid["h"] = sh
            solid["tag"] = np.zeros(10, dtype=np.int32)
            solid["m"] = np.full(10, 0.75, dtype=dtype)


def h5part(h5py, np, path):
    """H5Part: Step#N groups of 1-D arrays; step 1 moves every particle by +1 in x."""
    pos, vel, rho, _, ids = columns(np, np.float64)
    with h5py.File(path, "w") as f:
        for step in (0, 1):
            g = f.create_group("Step#%d" % step)
            g.attrs["TimeValue"] = 0.1 * step
            for k, name in enumerate("xyz"):
                g[name] = pos[:, k] + (step if k == 0 else 0)
            g["id"] = ids.astype(np.int64)
            for k, name in enumerate(("vx", "vy", "vz")):
                g[name] = vel[:, k]


def custom(h5py, np, path):
    pos, _, _, _, _ = columns(np, np.float32)
    with h5py.File(path, "w") as f:
        f["sim/pos"] = pos
        for k, name in enumerate("abc"):
            f["cols/" + name] = pos[:, k].astype(np.float64)


def broken(h5py, np, out):
    pos, _, rho, _, _ = columns(np, np.float32)
    with h5py.File(os.path.join(out, "wrong_rank.h5"), "w") as f:
        f["PartType0/Coordinates"] = pos[:, 0]
    with h5py.File(os.path.join(out, "wrong_shape.h5"), "w") as f:
        f["PartType0/Coordinates"] = np.zeros((N, 4), dtype=np.float32)
    with h5py.File(os.path.join(out, "mismatch.h5"), "w") as f:
        f["PartType0/Coordinates"] = pos
        f["PartType0/Density"] = rho[:N - 1]
    with h5py.File(os.path.join(out, "mismatch_xyz.h5"), "w") as f:
        f["x"] = pos[:, 0]
        f["y"] = pos[:N - 1, 1]
        f["z"] = pos[:, 2]
    with h5py.File(os.path.join(out, "huge.h5"), "w") as f:
        f.create_dataset("PartType0/Coordinates", shape=(2**40, 3), dtype=np.float32, chunks=(1024, 3))
    with h5py.File(os.path.join(out, "unwritten.h5"), "w") as f:
        f.create_dataset("PartType0/Coordinates", shape=(N, 3), dtype=np.float32, chunks=(10, 3))
    with h5py.File(os.path.join(out, "strings.h5"), "w") as f:
        f["PartType0/Coordinates"] = np.array([b"a", b"b"])
    with h5py.File(os.path.join(out, "nan.h5"), "w") as f:
        bad = pos.copy()
        bad[7, 1] = np.nan
        f["PartType0/Coordinates"] = bad
    with h5py.File(os.path.join(out, "no_particles.h5"), "w") as f:
        f.create_group("Header").attrs["BoxSize"] = 1.0
    with h5py.File(os.path.join(out, "ids_too_big.h5"), "w") as f:
        f["PartType0/Coordinates"] = pos
        f["PartType0/ParticleIDs"] = np.full(N, 2**40, dtype=np.uint64)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    try:
        import h5py
        import numpy as np
    except ImportError:
        print("make_hdf5_fixtures: h5py not found (apt-get install python3-h5py)")
        return 77
    swift(h5py, np, os.path.join(out, "swift_f32.h5"), np.float32, True)
    swift(h5py, np, os.path.join(out, "swift_f64.hdf5"), np.float64, True)
    swift(h5py, np, os.path.join(out, "swift_minimal.h5"), np.float64, False)
    swift(h5py, np, os.path.join(out, "userblock.h5"), np.float32, False, userblock=1024)
    shutil.copy(os.path.join(out, "swift_f32.h5"), os.path.join(out, "snapshot_0000"))  # no extension
    pysph(h5py, np, os.path.join(out, "pysph_f64.hdf5"), np.float64, True)
    pysph(h5py, np, os.path.join(out, "pysph_f32.hdf5"), np.float32, False)
    h5part(h5py, np, os.path.join(out, "steps.h5part"))
    custom(h5py, np, os.path.join(out, "custom.h5"))
    broken(h5py, np, out)
    print("make_hdf5_fixtures: wrote", len(os.listdir(out)), "files to", out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
