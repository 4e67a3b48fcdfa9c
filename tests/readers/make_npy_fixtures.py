#!/usr/bin/env python3
"""Writes the .npy files test_reader_npy reads, with numpy's own writer.

Usage: make_npy_fixtures.py DIR
Without numpy (Debian: python3-numpy) it writes nothing and says so; the C test
then checks its byte-built files only. Particle i's coordinate k is
(3 i + k) * 0.25 - 1.5, the formula the C test checks against."""
import os
import sys

N = 1000


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    try:
        import numpy as np
    except ImportError:
        print("make_npy_fixtures: numpy not found (apt-get install python3-numpy): no numpy-written files")
        return 0
    a = (np.arange(3 * N, dtype=np.float64).reshape(N, 3)) * 0.25 - 1.5
    np.save(os.path.join(out, "f32_v1.npy"), a.astype(np.float32))
    np.save(os.path.join(out, "f64_v1.npy"), a)
    with open(os.path.join(out, "f32_v2.npy"), "wb") as f:
        np.lib.format.write_array(f, a.astype(np.float32), version=(2, 0))
    np.save(os.path.join(out, "fortran.npy"), np.asfortranarray(a.astype(np.float32)))
    np.save(os.path.join(out, "big_endian.npy"), a.astype(">f8"))
    # Refused: integers, a structured array, a flat array, four columns.
    np.save(os.path.join(out, "int32.npy"), a.astype(np.int32))
    rec = np.zeros(N, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4")])
    np.save(os.path.join(out, "structured.npy"), rec)
    np.save(os.path.join(out, "flat.npy"), a.astype(np.float32).ravel())
    np.save(os.path.join(out, "four_columns.npy"), np.zeros((N, 4), dtype=np.float32))
    return 0


if __name__ == "__main__":
    sys.exit(main())
