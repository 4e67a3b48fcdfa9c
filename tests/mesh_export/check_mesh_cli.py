#!/usr/bin/env python3
"""fluidcast mesh end to end: a real fluidcastd extracts the surfaces of two
frames of a ball (a %04d pattern) and the command writes them; VTK's readers
read every format back with the counts of the same mesh, the surfaces closed;
--skip-existing leaves the files written; a sequence into one file is a usage
error (exit 2).

usage: check_mesh_cli.py FLUIDCAST FLUIDCASTD WORK_DIR   (exit 77 without VTK)"""
import os
import shutil
import subprocess
import sys
import time

try:
    import numpy as np
    import vtk
except ImportError:
    print("python3-vtk9 or numpy missing: skipped")
    sys.exit(77)

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def ball(seed, count=3000):
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(count, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    p *= 0.5 * rng.random(count)[:, None] ** (1 / 3)
    return p.astype("<f4")


def read(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def closed(poly):
    edges = vtk.vtkFeatureEdges()
    edges.SetInputData(poly)
    edges.BoundaryEdgesOn(), edges.NonManifoldEdgesOn(), edges.FeatureEdgesOff(), edges.ManifoldEdgesOff()
    edges.Update()
    return edges.GetOutput().GetNumberOfCells() == 0


def start_daemon(fluidcastd, work):
    port_file = os.path.join(work, "port")
    log = open(os.path.join(work, "fluidcastd.log"), "w")
    daemon = subprocess.Popen([fluidcastd, "--listen", "127.0.0.1:0", "--port-file", port_file], stdout=log,
                              stderr=subprocess.STDOUT)
    for _ in range(600):
        if os.path.exists(port_file) and open(port_file).read().strip():
            return daemon, "127.0.0.1:" + open(port_file).read().strip()
        if daemon.poll() is not None:
            break
        time.sleep(0.1)
    daemon.kill()
    sys.exit("fluidcastd did not start; see %s" % log.name)


def main():
    fluidcast, fluidcastd, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for number in (1, 2):
        ball(number).tofile(os.path.join(work, "ball_%04d.f32" % number))
    daemon, address = start_daemon(fluidcastd, work)
    try:
        def mesh(*args):
            return subprocess.run([fluidcast, "mesh", *args, "--server", address, "--radius", "0.05"],
                                  capture_output=True, text=True, cwd=work, timeout=300)

        run = mesh("ball_%04d.f32", "-o", "meshes/ball_%04d.vtp")
        check(run.returncode == 0, "sequence to .vtp: %s" % run.stderr)
        vtps = [read(vtk.vtkXMLPolyDataReader, os.path.join(work, "meshes/ball_%04d.vtp" % n)) for n in (1, 2)]
        for n, poly in zip((1, 2), vtps):
            check(poly.GetNumberOfPolys() > 100 and closed(poly), "ball_%04d.vtp: not a closed surface" % n)
        v, t = vtps[0].GetNumberOfPoints(), vtps[0].GetNumberOfPolys()
        check(vtps[0].GetPointData().GetNormals() is not None, ".vtp: no normals")

        written = os.path.getmtime(os.path.join(work, "meshes/ball_0001.vtp"))
        again = mesh("ball_%04d.f32", "-o", "meshes/ball_%04d.vtp", "--skip-existing")
        check(again.returncode == 0 and "skipping 2 frames" in again.stdout, "--skip-existing: %s" % again.stdout)
        check(os.path.getmtime(os.path.join(work, "meshes/ball_0001.vtp")) == written, "--skip-existing rewrote")

        for ext, reader in ((".ply", vtk.vtkPLYReader), (".obj", vtk.vtkOBJReader), (".stl", vtk.vtkSTLReader)):
            run = mesh("ball_0001.f32", "-o", "one" + ext)
            check(run.returncode == 0, "%s: %s" % (ext, run.stderr))
            poly = read(reader, os.path.join(work, "one" + ext))
            check(poly.GetNumberOfPolys() == t, "%s: %d triangles, .vtp %d" % (ext, poly.GetNumberOfPolys(), t))
            check(poly.GetNumberOfPoints() == v, "%s: %d points, .vtp %d" % (ext, poly.GetNumberOfPoints(), v))
            check(closed(poly), "%s: not closed" % ext)

        run = mesh("ball_%04d.f32", "-o", "one.obj")
        check(run.returncode == 2 and "%d" in run.stderr, "a sequence into one file: %d %s" % (run.returncode,
                                                                                             run.stderr))
        check(daemon.poll() is None, "fluidcastd exited")
    finally:
        daemon.terminate()
        daemon.wait(timeout=60)
    if failures:
        sys.exit(1)
    print("fluidcast mesh: 2 frames, %d vertices and %d triangles in frame 1, in .vtp, .ply, .obj and .stl" % (v, t))


if __name__ == "__main__":
    main()
