#!/usr/bin/python3
"""vtk_fluid_bench.py - the peer side of bench/run_bench.sh: times VTK's
vtkOpenGLFluidMapper (narrow-range filter) on the particles fluidcast-bench
renders, with the same radius, camera and image size.

    fluidcast-bench --particles 64k --write-scene /tmp/drop.f32   # prints the radius
    xvfb-run -a env LIBGL_ALWAYS_SOFTWARE=1 /usr/bin/python3 vtk_fluid_bench.py \\
        --scene /tmp/drop.f32 --radius 0.0187553 --size 1280x720 --frames 5 --image vtk.png

Needs Debian's python3-vtk9 (VTK 9.1), hence /usr/bin/python3, and an X
display (xvfb-run gives one). Prints the GL renderer, then one markdown row:

    | particles | size | filter | iter | first frame ms | wall/frame | fps |

A frame's wall time is Render() plus reading the RGBA8 pixels back, which
waits for the GPU like glFinish and matches fluidcast-bench, whose frames
also end with the readback of the image.
"""
import argparse
import statistics
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow, vtkVolume, vtkWindowToImageFilter
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLFluidMapper

# The drop scene's camera (bench/scene.c, bench_scene_drop_camera).
EYE = (2.0, -2.9, 1.9)
TARGET = (0.0, 0.0, 0.25)
UP = (0.0, 0.0, 1.0)
FOV_Y_DEG = 40.0

# VTK 9.1 does not wrap the uint32_t setters (SetSurfaceFilterIterations,
# SetSurfaceFilterRadius) for Python, so the filter runs with its defaults.
VTK_DEFAULT_FILTER_ITERATIONS = 3


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", required=True, help="particles as .f32 (little-endian float32 xyz)")
    p.add_argument("--radius", required=True, type=float, help="sphere radius, world units")
    p.add_argument("--size", default="1280x720", help="WIDTHxHEIGHT")
    p.add_argument("--frames", default=5, type=int, help="timed frames after one warm-up frame")
    p.add_argument("--image", help="write the last frame here as PNG")
    args = p.parse_args()
    try:
        args.width, args.height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        p.error(f"bad --size '{args.size}'")
    if args.width < 1 or args.height < 1 or args.frames < 1 or args.radius <= 0:
        p.error("--size, --frames and --radius must be positive")
    return args


def load_points(path):
    xyz = np.fromfile(path, dtype="<f4")
    if xyz.size == 0 or xyz.size % 3:
        sys.exit(f"vtk_fluid_bench: {path}: not a .f32 particle file ({xyz.size} floats)")
    points = vtkPoints()
    points.SetData(numpy_to_vtk(xyz.reshape(-1, 3), deep=True))
    poly = vtkPolyData()
    poly.SetPoints(points)
    return poly


def make_mapper(poly, radius):
    mapper = vtkOpenGLFluidMapper()
    mapper.SetInputData(poly)
    mapper.SetParticleRadius(radius)
    mapper.SetSurfaceFilterMethod(vtkOpenGLFluidMapper.NarrowRange)
    mapper.SetDisplayMode(vtkOpenGLFluidMapper.TransparentFluidVolume)
    # VTK's own "blue water" example values
    mapper.SetAttenuationColor(0.8, 0.2, 0.15)
    mapper.SetAttenuationScale(1.0)
    mapper.SetRefractiveIndex(1.33)
    return mapper


def make_window(mapper, width, height):
    renderer = vtkRenderer()
    renderer.SetBackground(0.55, 0.62, 0.70)
    # VTK's fluid test removes the frustum culler too: it culls the volume otherwise.
    renderer.RemoveCuller(renderer.GetCullers().GetLastItem())
    volume = vtkVolume()
    volume.SetMapper(mapper)
    renderer.AddVolume(volume)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(*EYE)
    camera.SetFocalPoint(*TARGET)
    camera.SetViewUp(*UP)
    camera.SetViewAngle(FOV_Y_DEG)
    renderer.ResetCameraClippingRange()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    return window, renderer


def render_frame_ms(window, renderer, pixels):
    """One frame: Render(), then the RGBA8 readback, which waits for the GPU."""
    width, height = window.GetSize()
    t0 = time.perf_counter()
    renderer.ResetCameraClippingRange()
    window.Render()
    window.GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, pixels)
    return (time.perf_counter() - t0) * 1e3


def gl_renderer(window):
    for line in window.ReportCapabilities().splitlines():
        if line.startswith("OpenGL renderer string:"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def save_png(window, path):
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def main():
    args = parse_args()
    poly = load_points(args.scene)
    window, renderer = make_window(make_mapper(poly, args.radius), args.width, args.height)
    pixels = vtkUnsignedCharArray()
    first_ms = render_frame_ms(window, renderer, pixels)  # shader compilation, buffers
    print(f"GL_RENDERER: {gl_renderer(window)}")
    wall = statistics.median(render_frame_ms(window, renderer, pixels) for _ in range(args.frames))
    if args.image:
        save_png(window, args.image)
    print(f"| {poly.GetNumberOfPoints()} | {args.width}x{args.height} | vtk narrow-range |"
          f" {VTK_DEFAULT_FILTER_ITERATIONS} | {first_ms:.2f} | {wall:.2f} | {1000.0 / wall:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
