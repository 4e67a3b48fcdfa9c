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
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_scene  # noqa: E402  (particles, the fluid mapper, window, PNG: shared with vtk_fluid_image.py)
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkRenderer  # noqa: E402

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
    p.add_argument("--scene", required=True, help="particles as .f32 (little-endian float32 xyz) or binary .ply")
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


def make_window(poly, radius, width, height):
    renderer = vtkRenderer()
    renderer.SetBackground(0.55, 0.62, 0.70)
    vtk_scene.remove_frustum_culler(renderer)
    renderer.AddVolume(vtk_scene.fluid_volume(vtk_scene.make_fluid_mapper(poly, radius)))
    vtk_scene.set_camera(renderer, EYE, TARGET, UP, FOV_Y_DEG)
    return vtk_scene.make_window(renderer, width, height), renderer


def render_frame_ms(window, renderer, pixels):
    """One frame: Render(), then the RGBA8 readback, which waits for the GPU."""
    width, height = window.GetSize()
    t0 = time.perf_counter()
    renderer.ResetCameraClippingRange()
    window.Render()
    window.GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, pixels)
    return (time.perf_counter() - t0) * 1e3


def main():
    args = parse_args()
    poly = vtk_scene.points_polydata(vtk_scene.load_particles_or_exit(args.scene, "vtk_fluid_bench"))
    window, renderer = make_window(poly, args.radius, args.width, args.height)
    pixels = vtkUnsignedCharArray()
    first_ms = render_frame_ms(window, renderer, pixels)  # shader compilation, buffers
    print(f"GL_RENDERER: {vtk_scene.gl_renderer(window)}")
    wall = statistics.median(render_frame_ms(window, renderer, pixels) for _ in range(args.frames))
    if args.image:
        vtk_scene.write_png(args.image, vtk_scene.window_rgb(window))
    print(f"| {poly.GetNumberOfPoints()} | {args.width}x{args.height} | vtk narrow-range |"
          f" {VTK_DEFAULT_FILTER_ITERATIONS} | {first_ms:.2f} | {wall:.2f} | {1000.0 / wall:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
