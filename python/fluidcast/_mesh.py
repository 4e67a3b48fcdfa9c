"""Mesh: numpy triangle-mesh arrays viewed as an fc_mesh, copied only when they must be."""

import ctypes

import numpy as np

from ._capi import FcMesh, FcMeshTransform
from ._enums import MESH_HIDE_NEAR, Code
from ._errors import Error
from ._frame import _as_array

_UINT32_MAX = 0xFFFFFFFF
_IDENTITY = (1.0, 0.0, 0.0, 0.0,
             0.0, 1.0, 0.0, 0.0,
             0.0, 0.0, 1.0, 0.0)


def as_transform(what, transform):
    """The 12 floats of fc_mesh.transform (3x4 row-major, world = R v + t) from Python values.

    ``transform``: None (identity); a 3x4 matrix (rows r0 r1 r2 with t as the
    last column); a 4x4 homogeneous matrix whose last row is (0, 0, 0, 1); or
    12 numbers, row-major. ValueError otherwise; libfluidcast checks the values.
    """
    if transform is None:
        return _IDENTITY
    matrix = np.asarray(transform, dtype=np.float64)
    if matrix.shape == (4, 4):
        if not np.array_equal(matrix[3], (0.0, 0.0, 0.0, 1.0)):
            raise ValueError("%s: a 4x4 matrix must end with the row (0, 0, 0, 1), got %s" % (what, matrix[3]))
        matrix = matrix[:3]
    if matrix.shape not in ((3, 4), (12,)):
        raise ValueError("%s: expected a 3x4 or 4x4 matrix or 12 numbers, got shape %s" % (what, matrix.shape))
    return tuple(float(v) for v in matrix.reshape(-1))


def _mesh_id(value):
    value = int(value)
    if not 0 <= value <= _UINT32_MAX:
        raise ValueError("mesh id: %d does not fit uint32" % value)
    return value


def _as_indices(indices):
    """Indices as a C-contiguous (T, 3) uint32 array (the caller's own when it is one), and whether it was copied.

    Takes (T, 3) or flat (3T,) integer arrays. A negative index, or one beyond
    uint32, raises Error(INVALID_VALUE) naming the triangle, as libfluidcast
    does for an index >= the vertex count.
    """
    array = np.asarray(indices)
    if array.ndim == 1 and array.size % 3 == 0:
        array = array.reshape(-1, 3)    # a view of the same memory when it can be one
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError("indices: expected shape (T, 3) or (3T,), got %s" % (np.shape(indices),))
    if array.dtype.kind not in "iu":
        raise TypeError("indices: expected integers, got an array of dtype %s" % array.dtype)
    if array.dtype != np.uint32 and array.size:
        bad = np.flatnonzero(((array < 0) | (array > _UINT32_MAX)).any(axis=1))
        if bad.size:
            t = int(bad[0])
            raise Error(Code.INVALID_VALUE, "triangle %d has index %s, outside uint32"
                        % (t, array[t][(array[t] < 0) | (array[t] > _UINT32_MAX)][0]))
    converted = np.require(array, dtype=np.uint32, requirements=("C_CONTIGUOUS", "ALIGNED"))
    source = indices if isinstance(indices, np.ndarray) else None
    copied = not (source is not None and converted.ctypes.data == source.ctypes.data
                  and source.dtype == np.uint32)
    return converted, copied


class Mesh:
    """A triangle mesh ready to send, viewed as an fc_mesh (PROTOCOL.md section 12).

    Arguments (numpy arrays or anything ``numpy.asarray`` takes):
        vertices: shape (V, 3), x y z per vertex in the mesh's own frame.
        indices: shape (T, 3) (or flat (3T,)), vertex indices of each triangle,
            counter-clockwise seen from outside, each < V.
        normals: shape (V, 3), one per vertex, or None for flat faces from the winding.
        id: which of the connection's meshes this is (a later mesh of the same id replaces it).
        color: linear RGB, each in [0, 1].
        opacity: in [0, 1]; 1 is opaque (hides the fluid behind it), below 1 glass drawn over the fluid.
        transform: where the mesh stands: None (identity), a 3x4 (R | t) or 4x4
            matrix, or 12 numbers row-major (world = R v + t).
        hide_near: True for FC_MESH_HIDE_NEAR: faces turned toward the camera
            are not drawn, so a tank's near walls do not hide the fluid inside.

    Like :class:`Frame`, no copy is made of an array that already is
    C-contiguous and aligned with the type fc_mesh holds (float32 vertices and
    normals, uint32 indices): the fc_mesh points into the array itself and
    libfluidcast encodes the message from there. Others (float64, int64
    indices, strided views) are converted once; ``copied`` names them. Values
    are checked by libfluidcast when the mesh is sent.
    """

    def __init__(self, vertices, indices, normals=None, id=0, color=(0.8, 0.8, 0.8), opacity=1.0,
                 transform=None, hide_near=False):
        self.vertices, c_vertices = _as_array("vertices", vertices, np.float32, 3, None)
        self.indices, c_indices = _as_indices(indices)
        self.normals = None
        copied = (["vertices"] if c_vertices else []) + (["indices"] if c_indices else [])
        if normals is not None:
            self.normals, c_normals = _as_array("normals", normals, np.float32, 3, self.vertices.shape[0])
            copied += ["normals"] if c_normals else []
        #: names of the arrays that had to be converted (copied), e.g. ("indices",) for int64 input
        self.copied = tuple(copied)
        for name, count in (("vertices", self.vertices.shape[0]), ("indices", self.indices.shape[0])):
            if count > _UINT32_MAX:
                raise Error(Code.LIMIT, "%s: %d rows do not fit uint32" % (name, count))
        self.id = _mesh_id(id)
        color = tuple(float(v) for v in color)
        if len(color) != 3:
            raise ValueError("color: expected 3 numbers, got %d" % len(color))

        def pointer(array, ctype):
            return None if array is None else array.ctypes.data_as(ctypes.POINTER(ctype))

        #: the fc_mesh handed to libfluidcast; its pointers address the arrays above
        self.c_mesh = FcMesh(self.id, MESH_HIDE_NEAR if hide_near else 0, self.vertices.shape[0],
                             self.indices.shape[0], pointer(self.vertices, ctypes.c_float),
                             pointer(self.indices, ctypes.c_uint32), pointer(self.normals, ctypes.c_float),
                             (ctypes.c_float * 3)(*color), float(opacity),
                             (ctypes.c_float * 12)(*as_transform("transform", transform)))

    @property
    def vertex_count(self):
        return self.c_mesh.vertex_count

    @property
    def triangle_count(self):
        return self.c_mesh.triangle_count

    def __repr__(self):
        return "<fluidcast.Mesh %d: %d vertices, %d triangles%s%s>" % (
            self.id, self.vertex_count, self.triangle_count, ", normals" if self.normals is not None else "",
            " (copied: %s)" % ", ".join(self.copied) if self.copied else "")


def as_mesh(vertices, indices=None, **kw):
    """A Mesh from arrays, or ``vertices`` itself when it is a Mesh (then nothing else may be given)."""
    if isinstance(vertices, Mesh):
        if indices is not None or any(v is not None for v in kw.values()):
            raise TypeError("pass either a Mesh or arrays, not both")
        return vertices
    if indices is None:
        raise TypeError("upload_mesh: indices are required with vertices")
    return Mesh(vertices, indices, **{k: v for k, v in kw.items() if v is not None})


def transform_entries(transforms):
    """An array of fc_mesh_transform from {id: transform} or an iterable of (id, transform) pairs."""
    pairs = list(transforms.items() if hasattr(transforms, "items") else transforms)
    entries = (FcMeshTransform * max(len(pairs), 1))()
    for entry, pair in zip(entries, pairs):
        try:
            mesh_id, transform = pair
        except (TypeError, ValueError):
            raise TypeError("move_meshes: expected (id, transform) pairs, got %r" % (pair,)) from None
        entry.id = _mesh_id(mesh_id)
        entry.transform = (ctypes.c_float * 12)(*as_transform("transform of mesh %d" % entry.id, transform))
    return entries, len(pairs)
