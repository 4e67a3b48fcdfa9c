"""fluidcast: send particle frames from Python to a fluidcastd render daemon and get images back.

A pure-Python binding over libfluidcast.so (ctypes); numpy arrays go to the
socket without a copy when they are already C-contiguous float32::

    import numpy as np, fluidcast
    with fluidcast.connect("render-host:7450") as c:
        c.send_frame(np.random.rand(10000, 3).astype(np.float32))
        c.set_camera(eye=(2, -3, 2), target=(0.5, 0.5, 0.5), size=(640, 360))
        c.set_settings(radius=0.02)
        open("fluid.png", "wb").write(c.render("png"))

Every failing call raises :class:`Error` with the fc_code (:class:`Code`) and
the library's (or the server's) message. Importing the package loads
libfluidcast: see :mod:`fluidcast._library` for where it is looked for
($FLUIDCAST_LIBRARY first).
"""

from ._enums import (Aov, Code, ColorBy, Colormap, Format, JpegSubsampling, Kernel, MESH_HIDE_NEAR,
                     SERVER_CAN_DEVICE, SERVER_CAN_QUANTIZE16, SERVER_CAN_STREAM, SERVER_CAN_ZSTD, Smoothing, Stage,
                     SURFACE_DENSITY, SURFACE_ID, SURFACE_SPEED, SURFACE_VELOCITY, SurfaceKernel, SurfaceMode)
from ._errors import Error
from ._frame import Frame
from ._mesh import Mesh
from ._surface import SurfaceMesh
from ._capi import library_path
from ._client import (Client, Image, SETTING_NAMES, ServerInfo, SessionStatus, StreamImage, UploadStats, connect,
                      default_settings)

__all__ = [
    "connect", "Client", "Error", "Code", "Frame", "Mesh", "Image", "StreamImage", "ServerInfo", "SessionStatus",
    "UploadStats", "Format", "Aov", "Smoothing", "Kernel", "ColorBy", "Colormap", "JpegSubsampling", "Stage",
    "SurfaceMode", "SurfaceKernel",
    "SETTING_NAMES", "default_settings", "SERVER_CAN_STREAM", "SERVER_CAN_ZSTD", "SERVER_CAN_QUANTIZE16",
    "SERVER_CAN_DEVICE", "MESH_HIDE_NEAR", "SurfaceMesh", "SURFACE_SPEED", "SURFACE_DENSITY", "SURFACE_VELOCITY",
    "SURFACE_ID",
    "library_path",
]
