#!/usr/bin/env python3
"""The files of fluidcast mesh's writers read back by VTK's own readers
(python3-vtk9): write_test_meshes writes one closed sphere of V vertices and
T triangles (attributes set from the position) as .ply, .obj, .vtp and .stl;
each must come back with T triangles and V points (STL: V once merged), the
formats that carry them with the normals and the attributes, value for value.

usage: check_mesh_files.py WRITE_TEST_MESHES WORK_DIR   (exit 77 without VTK)"""
import os
import subprocess
import sys

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    import numpy as np
except ImportError:
    print("python3-vtk9 or numpy missing: skipped")
    sys.exit(77)

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def read(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def triangles_only(poly):
    cells = poly.GetPolys()
    sizes = np.diff(vtk_to_numpy(cells.GetOffsetsArray()))
    return len(sizes) > 0 and bool(np.all(sizes == 3))


def expected_attributes(points):
    """What write_test_meshes sets from each position p (the unit sphere about (1, 2, 3))."""
    n = points - np.array([1.0, 2.0, 3.0])
    return {"speed": 2.0 + n[:, 2], "density": 1000.0 + n[:, 0],
            "velocity": n[:, 2:3] * np.array([1.0, 2.0, 3.0])}


def check_attributes(name, poly, arrays):
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    want = expected_attributes(points)
    for attribute, values in want.items():
        got = arrays(attribute)
        check(got is not None, f"{name}: no {attribute}")
        if got is not None:
            got = got.reshape(values.shape)
            check(np.allclose(got, values, atol=2e-6), f"{name}: {attribute} differs")
    ids = arrays("id")
    check(ids is not None and len(np.unique(ids)) == len(points), f"{name}: ids missing or repeated")


def main():
    writer, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    out = subprocess.run([writer, work], check=True, capture_output=True, text=True).stdout.split()
    v, t = int(out[0]), int(out[1])

    ply = read(vtk.vtkPLYReader, os.path.join(work, "sphere.ply"))
    check(ply.GetNumberOfPoints() == v and ply.GetNumberOfPolys() == t, "ply: counts")
    check(triangles_only(ply), "ply: not all triangles")
    check(ply.GetPointData().GetNormals() is not None, "ply: no normals")
    # vtkPLYReader keeps only the properties it knows (normals, colours, texture
    # coordinates): the attributes are read from the file itself below.
    check_ply_properties(os.path.join(work, "sphere.ply"), v, t)

    obj = read(vtk.vtkOBJReader, os.path.join(work, "sphere.obj"))
    check(obj.GetNumberOfPoints() == v and obj.GetNumberOfPolys() == t, f"obj: counts {obj.GetNumberOfPoints()} {obj.GetNumberOfPolys()}")
    check(obj.GetPointData().GetNormals() is not None, "obj: no normals")

    vtp = read(vtk.vtkXMLPolyDataReader, os.path.join(work, "sphere.vtp"))
    check(vtp.GetNumberOfPoints() == v and vtp.GetNumberOfPolys() == t, "vtp: counts")
    check(triangles_only(vtp), "vtp: not all triangles")
    check(vtp.GetPointData().GetNormals() is not None, "vtp: no normals")
    pd = vtp.GetPointData()
    check_attributes("vtp", vtp, lambda a: None if pd.GetArray(a) is None else vtk_to_numpy(pd.GetArray(a)))

    stl = read(vtk.vtkSTLReader, os.path.join(work, "sphere.stl"))
    check(stl.GetNumberOfPolys() == t, "stl: triangle count")
    check(stl.GetNumberOfPoints() == v, f"stl: {stl.GetNumberOfPoints()} merged points, expected {v}")

    # A closed surface: every edge in exactly two triangles, the same in every format.
    for name, poly in (("ply", ply), ("vtp", vtp), ("stl", stl), ("obj", obj)):
        edges = vtk.vtkFeatureEdges()
        edges.SetInputData(poly)
        edges.BoundaryEdgesOn(), edges.NonManifoldEdgesOn(), edges.FeatureEdgesOff(), edges.ManifoldEdgesOff()
        edges.Update()
        check(edges.GetOutput().GetNumberOfCells() == 0, f"{name}: open or non-manifold edges")

    empty = read(vtk.vtkXMLPolyDataReader, os.path.join(work, "empty.vtp"))
    check(empty.GetNumberOfPoints() == 0, "empty.vtp: points")
    empty_ply = read(vtk.vtkPLYReader, os.path.join(work, "empty.ply"))
    check(empty_ply.GetNumberOfPoints() == 0, "empty.ply: points")
    if failures:
        sys.exit(1)
    print(f"ply, obj, vtp, stl: {v} vertices, {t} triangles each, read back by VTK {vtk.vtkVersion.GetVTKVersion()}")


def check_ply_properties(path, v, t):
    """The binary PLY parsed with numpy from its own header: the attributes' values."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    names = [line.split()[2] for line in header if line.startswith("property float") or line.startswith("property uint")]
    check(names == ["x", "y", "z", "nx", "ny", "nz", "speed", "density", "vx", "vy", "vz", "id"],
          f"ply: properties {names}")
    record = np.dtype([(n, "<u4" if n == "id" else "<f4") for n in names])
    vertices = np.frombuffer(data, dtype=record, count=v, offset=end)
    faces = np.frombuffer(data, dtype=np.dtype([("n", "u1"), ("i", "<u4", 3)]), count=t,
                          offset=end + v * record.itemsize)
    check(end + v * record.itemsize + t * 13 == len(data), "ply: file size")
    check(bool(np.all(faces["n"] == 3)) and int(faces["i"].max()) == v - 1, "ply: faces")
    points = np.stack([vertices["x"], vertices["y"], vertices["z"]], axis=1).astype(np.float64)
    want = expected_attributes(points)
    check(np.allclose(vertices["speed"], want["speed"], atol=2e-6), "ply: speed differs")
    check(np.allclose(vertices["density"], want["density"], atol=2e-4), "ply: density differs")
    velocity = np.stack([vertices["vx"], vertices["vy"], vertices["vz"]], axis=1)
    check(np.allclose(velocity, want["velocity"], atol=2e-6), "ply: velocity differs")
    check(len(np.unique(vertices["id"])) == v, "ply: ids repeated")


if __name__ == "__main__":
    main()
