#!/usr/bin/env python3
"""Writes the .vtp meshes test_mesh_readers reads, with VTK's own
vtkXMLPolyDataWriter: the quad-and-triangle mesh of the C test (5 points,
polygons 0 1 2 3 and 1 4 2, point Normals the reader skips) as ascii, inline
base64 binary, appended raw zlib (UInt64 headers) and appended base64
uncompressed (UInt32 headers); and a strips-only file the reader refuses.

Usage: make_vtp_mesh_fixtures.py DIR. Without VTK (Debian: python3-vtk9) it
writes nothing and says so; the C test then skips these cases."""
import os
import sys

POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 0.5, 1)]
POLYS = [(0, 1, 2, 3), (1, 4, 2)]


def build(vtk, strips):
    points = vtk.vtkPoints()
    points.SetDataTypeToFloat()
    normals = vtk.vtkFloatArray()
    normals.SetNumberOfComponents(3)
    normals.SetName("Normals")
    for p in POINTS:
        points.InsertNextPoint(*p)
        normals.InsertNextTuple3(0, 0, 1)
    cells = vtk.vtkCellArray()
    for poly in ([(0, 1, 3, 2)] if strips else POLYS):
        cells.InsertNextCell(len(poly))
        for i in poly:
            cells.InsertCellPoint(i)
    data = vtk.vtkPolyData()
    data.SetPoints(points)
    if strips:
        data.SetStrips(cells)
    else:
        data.SetPolys(cells)
    data.GetPointData().SetNormals(normals)
    return data


def write(vtk, path, data, mode, compressed, header64, raw=True):
    writer = vtk.vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    {"ascii": writer.SetDataModeToAscii, "binary": writer.SetDataModeToBinary,
     "appended": writer.SetDataModeToAppended}[mode]()
    if compressed:
        writer.SetCompressorTypeToZLib()
    else:
        writer.SetCompressorTypeToNone()
    writer.SetHeaderTypeToUInt64() if header64 else writer.SetHeaderTypeToUInt32()
    writer.SetEncodeAppendedData(0 if raw else 1)
    if writer.Write() != 1:
        sys.exit("vtkXMLPolyDataWriter failed on " + path)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    try:
        import vtk
    except ImportError:
        print("VTK (python3-vtk9) not installed: no .vtp mesh fixtures written")
        return
    os.makedirs(out, exist_ok=True)
    mesh = build(vtk, False)
    write(vtk, os.path.join(out, "ascii.vtp"), mesh, "ascii", False, False)
    write(vtk, os.path.join(out, "binary_zlib.vtp"), mesh, "binary", True, False)
    write(vtk, os.path.join(out, "appended_zlib.vtp"), mesh, "appended", True, True)
    write(vtk, os.path.join(out, "appended_base64.vtp"), mesh, "appended", False, False, raw=False)
    write(vtk, os.path.join(out, "strips.vtp"), build(vtk, True), "ascii", False, False)


if __name__ == "__main__":
    main()
