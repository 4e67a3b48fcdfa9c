"""vtk_scene.py - what the VTK peer scripts share (vtk_fluid_bench.py,
vtk_fluid_image.py): reading particle files into numpy, VTK's fluid mapper with
the settings fluidcast is compared at, the camera, the window, and PNG in/out.

Needs Debian's python3-vtk9 (VTK 9.1), hence /usr/bin/python3. Importing it
needs no display; rendering needs an X display (xvfb-run gives one).
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
# Registers the OpenGL implementations of vtkRenderer, vtkRenderWindow, the
# mappers, textures and lights: objects made before this import draw nothing.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401,E402

# The particle formats the VTK side reads. fluidcast also reads .vtk and .csv;
# convert those to .f32 or .ply for a comparison.
PARTICLE_FORMATS = (".ply", ".f32")

_PLY_TYPES = {
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
    "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
}


class ParticleFileError(Exception):
    pass


def _read_ply(path):
    """x, y, z of the first element of a binary little-endian PLY (the splash
    layout: x y z density vx vy vz float32, but any scalar properties work)."""
    raw = open(path, "rb").read()
    end = raw.find(b"end_header\n")
    if not raw.startswith(b"ply\n") or end < 0:
        raise ParticleFileError("not a PLY file (no 'ply' / 'end_header' lines)")
    body = end + len(b"end_header\n")
    count, fields, in_first = None, [], False
    for line in raw[:end].decode("ascii", "replace").splitlines()[1:]:
        words = line.split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "format" and words[1:2] != ["binary_little_endian"]:
            raise ParticleFileError(f"PLY format '{' '.join(words[1:])}': only binary_little_endian is read here")
        if words[0] == "element":
            if count is not None:
                break  # only the first element (the vertices) is read
            count, in_first = int(words[2]), True
        elif words[0] == "property" and in_first:
            if words[1] == "list" or words[1] not in _PLY_TYPES:
                raise ParticleFileError(f"PLY property '{' '.join(words[1:])}' is not a scalar type")
            fields.append((words[2], "<" + _PLY_TYPES[words[1]]))
    names = [name for name, _ in fields]
    if count is None or not all(axis in names for axis in "xyz"):
        raise ParticleFileError("PLY without an element that has x, y and z")
    record = np.dtype(fields)
    if len(raw) - body < count * record.itemsize:
        raise ParticleFileError(f"PLY body shorter than {count} records of {record.itemsize} bytes")
    a = np.frombuffer(raw, dtype=record, count=count, offset=body)
    return np.stack([a["x"], a["y"], a["z"]], axis=1).astype(np.float32)


def _read_f32(path):
    xyz = np.fromfile(path, dtype="<f4")
    if xyz.size == 0 or xyz.size % 3:
        raise ParticleFileError(f"not a .f32 particle file ({xyz.size} floats, not a multiple of 3)")
    return xyz.reshape(-1, 3)


def read_particles(path):
    """The particle centres in path (.ply or .f32) as an (N, 3) float32 array."""
    ext = os.path.splitext(path)[1].lower()
    try:
        if ext == ".ply":
            xyz = _read_ply(path)
        elif ext == ".f32":
            xyz = _read_f32(path)
        else:
            raise ParticleFileError(f"the VTK side reads {' and '.join(PARTICLE_FORMATS)} only")
    except OSError as e:
        raise ParticleFileError(e.strerror or str(e)) from e
    if not np.all(np.isfinite(xyz)):
        raise ParticleFileError("non-finite coordinates")
    return xyz


def load_particles_or_exit(path, prog):
    try:
        return read_particles(path)
    except ParticleFileError as e:
        sys.exit(f"{prog}: {path}: {e}")


def points_polydata(xyz):
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz, dtype=np.float32), deep=True))
    poly = vtkPolyData()
    poly.SetPoints(points)
    return poly


def make_fluid_mapper(poly, radius):
    """VTK's fluid mapper as the comparisons use it: narrow-range filter,
    transparent fluid volume, VTK's own "blue water" example values."""
    from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLFluidMapper
    mapper = vtkOpenGLFluidMapper()
    mapper.SetInputData(poly)
    mapper.SetParticleRadius(radius)
    mapper.SetSurfaceFilterMethod(vtkOpenGLFluidMapper.NarrowRange)
    mapper.SetDisplayMode(vtkOpenGLFluidMapper.TransparentFluidVolume)
    mapper.SetAttenuationColor(0.8, 0.2, 0.15)
    mapper.SetAttenuationScale(1.0)
    mapper.SetRefractiveIndex(1.33)
    return mapper


def fluid_volume(mapper):
    from vtkmodules.vtkRenderingCore import vtkVolume
    volume = vtkVolume()
    volume.SetMapper(mapper)
    return volume


def remove_frustum_culler(renderer):
    """VTK's fluid test removes the frustum culler: it culls the volume otherwise."""
    renderer.RemoveCuller(renderer.GetCullers().GetLastItem())


def set_camera(renderer, eye, target, up, fov_y_deg):
    camera = renderer.GetActiveCamera()
    camera.SetPosition(*eye)
    camera.SetFocalPoint(*target)
    camera.SetViewUp(*up)
    camera.SetViewAngle(fov_y_deg)
    renderer.ResetCameraClippingRange()


def make_window(renderers, width, height):
    from vtkmodules.vtkRenderingCore import vtkRenderWindow
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    if not isinstance(renderers, (list, tuple)):
        renderers = [renderers]
    window.SetNumberOfLayers(len(renderers))
    for layer, renderer in enumerate(renderers):
        renderer.SetLayer(layer)
        window.AddRenderer(renderer)
    return window


def gl_renderer(window):
    for line in window.ReportCapabilities().splitlines():
        if line.startswith("OpenGL renderer string:"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def window_rgb(window):
    """The window's back buffer as an (H, W, 3) uint8 array, top row first."""
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    return image_to_array(grab.GetOutput())


def image_to_array(image):
    """vtkImageData (2D, uint8, 1-4 components) -> (H, W, C) array, top row first."""
    w, h, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    a = vtk_to_numpy(scalars).reshape(h, w, scalars.GetNumberOfComponents())
    return np.ascontiguousarray(a[::-1])


def array_to_image(a):
    """(H, W, C) or (H, W) uint8 array, top row first -> vtkImageData."""
    if a.ndim == 2:
        a = a[:, :, None]
    h, w, c = a.shape
    image = vtkImageData()
    image.SetDimensions(w, h, 1)
    flat = np.ascontiguousarray(a[::-1]).reshape(-1, c)
    image.GetPointData().SetScalars(numpy_to_vtk(flat, deep=True))
    return image


def write_png(path, a):
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(array_to_image(np.asarray(a, dtype=np.uint8)))
    writer.Write()
    if writer.GetErrorCode():
        raise OSError(f"{path}: cannot write PNG")


def read_png(path):
    """A PNG as an (H, W, 3) uint8 array (alpha dropped, grey expanded), top row first."""
    reader = vtkPNGReader()
    if not reader.CanReadFile(path):
        raise OSError(f"{path}: not a readable PNG")
    reader.SetFileName(path)
    reader.Update()
    a = image_to_array(reader.GetOutput())
    if a.dtype != np.uint8:
        raise OSError(f"{path}: not an 8-bit PNG")
    if a.shape[2] in (1, 2):
        a = np.repeat(a[:, :, :1], 3, axis=2)
    return np.ascontiguousarray(a[:, :, :3])
