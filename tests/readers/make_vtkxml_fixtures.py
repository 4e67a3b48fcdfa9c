#!/usr/bin/env python3
"""Writes the VTK files test_reader_vtkxml reads, with VTK's own writers
(vtkXMLUnstructuredGridWriter, vtkXMLPolyDataWriter) in every data mode, and
legacy .vtk from vtkUnstructuredGridWriter and vtkPolyDataWriter.

Usage: make_vtkxml_fixtures.py DIR [N]
Writes DIR/*.vtu, *.vtp, series.pvd and DIR/manifest.txt (one file per line with
its point data names). Without VTK (Debian: python3-vtk9) it writes nothing and
says so; the C test then checks its byte-built files only.

Particle i (of N): position (0.5 i, -i, 2 i + 0.25), velocity (3 i, 3 i + 1,
3 i + 2) / 8, density 1000 + i / 4, id 1000000 + i: the formulas the C test checks."""
import os
import sys

N = 300


def build(vtk, double_points, polydata, names):
    points = vtk.vtkPoints()
    if double_points:
        points.SetDataTypeToDouble()
    else:
        points.SetDataTypeToFloat()
    velocity = vtk.vtkFloatArray()
    velocity.SetNumberOfComponents(3)
    velocity.SetName(names[0])
    density = vtk.vtkDoubleArray()
    density.SetName(names[1])
    ids = vtk.vtkTypeInt64Array()
    ids.SetName(names[2])
    pressure = vtk.vtkFloatArray()  # an array the reader skips
    pressure.SetName("pressure")
    for i in range(N):
        points.InsertNextPoint(0.5 * i, -i, 2 * i + 0.25)
        velocity.InsertNextTuple3(3 * i / 8, (3 * i + 1) / 8, (3 * i + 2) / 8)
        density.InsertNextValue(1000 + i / 4)
        ids.InsertNextValue(1000000 + i)
        pressure.InsertNextValue(-i)
    if polydata:
        data = vtk.vtkPolyData()
        data.SetPoints(points)
        verts = vtk.vtkCellArray()
        for i in range(N):
            verts.InsertNextCell(1)
            verts.InsertCellPoint(i)
        data.SetVerts(verts)
    else:
        data = vtk.vtkUnstructuredGrid()
        data.SetPoints(points)
        for i in range(N):
            data.InsertNextCell(vtk.VTK_VERTEX, 1, [i])
    for array in (pressure, velocity, density, ids):
        data.GetPointData().AddArray(array)
    return data


def main():
    global N
    out = sys.argv[1]
    if len(sys.argv) > 2:
        N = int(sys.argv[2])  # 4 makes the fuzz seeds (tests/fuzz/corpus/fuzz_reader_vtkxml)
    os.makedirs(out, exist_ok=True)
    try:
        import vtk
    except ImportError:
        print("make_vtkxml_fixtures: VTK not found (apt-get install python3-vtk9): no VTK-written files")
        return 0
    modes = {"ascii": 0, "binary": 1, "appended": 2}
    written = []
    for polydata in (False, True):
        names = ("Vel", "Rho", "Idp") if polydata else ("velocity", "density", "id")
        extension = "vtp" if polydata else "vtu"
        for mode in ("ascii", "binary", "appended", "raw"):
            for zlib in (False, True):
                for header64 in (False, True):
                    for double_points in (False, True):
                        if mode == "ascii" and (zlib or header64):
                            continue
                        data = build(vtk, double_points, polydata, names)
                        writer = vtk.vtkXMLPolyDataWriter() if polydata else vtk.vtkXMLUnstructuredGridWriter()
                        writer.SetInputData(data)
                        writer.SetDataMode(modes["appended" if mode == "raw" else mode])
                        if mode == "raw":
                            writer.EncodeAppendedDataOff()
                        if zlib:
                            writer.SetCompressorTypeToZLib()
                            writer.SetBlockSize(1024)  # several blocks per array
                        else:
                            writer.SetCompressorTypeToNone()
                        if header64:
                            writer.SetHeaderTypeToUInt64()
                        else:
                            writer.SetHeaderTypeToUInt32()
                        name = "%s_%s%s%s%s.%s" % ("poly" if polydata else "grid", mode, "_zlib" if zlib else "",
                                                   "_h64" if header64 else "", "_f64" if double_points else "",
                                                   extension)
                        writer.SetFileName(os.path.join(out, name))
                        if writer.Write() != 1:
                            print("make_vtkxml_fixtures: writing %s failed" % name)
                            return 1
                        written.append(name)
    # Legacy .vtk from VTK's legacy writers, ascii and binary, file versions 4.2 and 5.1 (the default).
    for polydata in (False, True):
        for binary in (False, True):
            for version in (42, 51):
                data = build(vtk, False, polydata, ("velocity", "density", "id"))
                writer = vtk.vtkPolyDataWriter() if polydata else vtk.vtkUnstructuredGridWriter()
                writer.SetInputData(data)
                if binary:
                    writer.SetFileTypeToBinary()
                else:
                    writer.SetFileTypeToASCII()
                if version == 42:
                    writer.SetFileVersion(42)
                name = "legacy_%s_%s_%d.vtk" % ("poly" if polydata else "grid", "binary" if binary else "ascii", version)
                writer.SetFileName(os.path.join(out, name))
                if writer.Write() != 1:
                    print("make_vtkxml_fixtures: writing %s failed" % name)
                    return 1
                written.append(name)
    # Big-endian, as a writer on such a machine would produce.
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetInputData(build(vtk, False, False, ("velocity", "density", "id")))
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetByteOrderToBigEndian()
    writer.SetFileName(os.path.join(out, "grid_raw_big_endian.vtu"))
    writer.Write()
    written.append("grid_raw_big_endian.vtu")
    # A collection as ParaView writes it, its datasets in a subdirectory.
    os.makedirs(os.path.join(out, "series"), exist_ok=True)
    for step in (0, 1):
        writer.SetFileName(os.path.join(out, "series", "step_%d.vtu" % step))
        writer.Write()
    with open(os.path.join(out, "series.pvd"), "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n')
        for step in (0, 1):
            f.write('    <DataSet timestep="%d" group="" part="0" file="series/step_%d.vtu"/>\n' % (step, step))
        f.write("  </Collection>\n</VTKFile>\n")
    with open(os.path.join(out, "manifest.txt"), "w") as f:
        for name in written:
            f.write(name + "\n")
    print("make_vtkxml_fixtures: wrote %d files" % len(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
