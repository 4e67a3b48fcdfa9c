"""SurfaceMesh: an extracted fluid surface (fc_surface_mesh) copied into numpy arrays."""

import ctypes
from typing import NamedTuple, Optional

import numpy as np

from ._enums import SURFACE_DENSITY, SURFACE_ID, SURFACE_SPEED, SURFACE_VELOCITY

#: Attribute names of :meth:`Client.mesh` and their bits.
SURFACE_ATTRIBUTES = {"speed": SURFACE_SPEED, "density": SURFACE_DENSITY, "velocity": SURFACE_VELOCITY,
                      "id": SURFACE_ID}


class SurfaceMesh(NamedTuple):
    """Welded, indexed triangles, counter-clockwise seen from outside, with unit outward normals.

    ``positions`` and ``normals`` are (V, 3) float32, ``triangles`` (T, 3)
    uint32 indices into them; ``speed`` and ``density`` (V,) float32,
    ``velocity`` (V, 3) float32 and ``id`` (V,) uint32 (the nearest particle's)
    are None when the mesh does not have them; ``extract_ms`` is the server's
    extraction time (negative when not measured).
    """
    positions: np.ndarray
    normals: np.ndarray
    triangles: np.ndarray
    speed: Optional[np.ndarray]
    density: Optional[np.ndarray]
    velocity: Optional[np.ndarray]
    id: Optional[np.ndarray]
    extract_ms: float


def attribute_bits(attributes):
    """"all", None (none), or an iterable of names ("speed", "density", "velocity", "id") -> FC_SURFACE_* bits."""
    if attributes is None:
        return 0
    if isinstance(attributes, str):
        attributes = list(SURFACE_ATTRIBUTES) if attributes == "all" else [attributes]
    bits = 0
    for name in attributes:
        if name not in SURFACE_ATTRIBUTES:
            raise ValueError("unknown surface attribute %r (speed, density, velocity, id)" % (name,))
        bits |= SURFACE_ATTRIBUTES[name]
    return bits


def _copy(pointer, count, dtype, columns):
    """A numpy copy of `count` rows of `columns` values at a C pointer (empty for none)."""
    shape = (count, columns) if columns > 1 else (count,)
    if count == 0 or not pointer:
        return np.zeros(shape, dtype=dtype)
    address = ctypes.cast(pointer, ctypes.c_void_p).value
    size = count * columns * np.dtype(dtype).itemsize
    buffer = (ctypes.c_char * size).from_address(address)
    return np.frombuffer(buffer, dtype=dtype).reshape(shape).copy()


def from_c(mesh, extract_ms):
    """Copies an FcSurfaceMesh's arrays (the caller frees it afterwards)."""
    v, t = mesh.vertex_count, mesh.triangle_count

    def optional(bit, pointer, dtype, columns):
        return _copy(pointer, v, dtype, columns) if mesh.attributes & bit else None

    return SurfaceMesh(positions=_copy(mesh.positions, v, np.float32, 3), normals=_copy(mesh.normals, v, np.float32, 3),
                       triangles=_copy(mesh.indices, t, np.uint32, 3),
                       speed=optional(SURFACE_SPEED, mesh.speed, np.float32, 1),
                       density=optional(SURFACE_DENSITY, mesh.density, np.float32, 1),
                       velocity=optional(SURFACE_VELOCITY, mesh.velocity, np.float32, 3),
                       id=optional(SURFACE_ID, mesh.id, np.uint32, 1), extract_ms=float(extract_ms))
