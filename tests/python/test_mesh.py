"""Mesh without a daemon: which arrays are encoded in place and which are copied,
transforms, and the checks made before anything is sent."""

import ctypes

import numpy as np
import pytest

import fluidcast
from fluidcast import _capi
from helpers import box


def address(pointer):
    return ctypes.cast(pointer, ctypes.c_void_p).value


def test_contiguous_float32_and_uint32_are_used_in_place():
    vertices, indices = box((-1, -1, -1), (1, 1, 1))
    normals = vertices / np.linalg.norm(vertices, axis=1)[:, None]
    mesh = fluidcast.Mesh(vertices, indices, normals=normals, id=7, color=(1, 0.5, 0), opacity=0.25,
                          hide_near=True)
    assert mesh.copied == ()
    assert mesh.vertices is vertices and mesh.indices is indices and mesh.normals is normals
    c = mesh.c_mesh
    assert (c.id, c.flags, c.vertex_count, c.triangle_count) == (7, fluidcast.MESH_HIDE_NEAR, 8, 12)
    assert address(c.vertices) == vertices.ctypes.data
    assert address(c.indices) == indices.ctypes.data
    assert address(c.normals) == normals.ctypes.data
    assert tuple(c.color) == (1.0, 0.5, 0.0) and c.opacity == 0.25
    # A flat (3T,) uint32 index array is viewed as (T, 3), still without a copy.
    flat = indices.reshape(-1).copy()
    mesh = fluidcast.Mesh(vertices, flat)
    assert mesh.copied == () and address(mesh.c_mesh.indices) == flat.ctypes.data


def test_other_types_are_converted_once():
    vertices, indices = box((0, 0, 0), (1, 2, 3))
    mesh = fluidcast.Mesh(vertices.astype(np.float64), indices.astype(np.int64))
    assert mesh.copied == ("vertices", "indices")
    assert mesh.vertices.dtype == np.float32 and mesh.indices.dtype == np.uint32
    np.testing.assert_array_equal(mesh.indices, indices)
    assert fluidcast.Mesh(vertices.tolist(), indices.tolist()).copied == ("vertices", "indices")
    assert fluidcast.Mesh(np.asfortranarray(vertices), indices).copied == ("vertices",)


def test_defaults_equal_fc_mesh_defaults():
    vertices, indices = box((0, 0, 0), (1, 1, 1))
    c = fluidcast.Mesh(vertices, indices).c_mesh
    defaults = _capi.FcMesh()
    _capi.fc_mesh_defaults(ctypes.byref(defaults))
    for name in ("id", "flags", "opacity"):
        assert getattr(c, name) == getattr(defaults, name), name
    assert tuple(c.color) == tuple(defaults.color) and tuple(c.transform) == tuple(defaults.transform)
    assert not c.normals


def test_transforms():
    vertices, indices = box((0, 0, 0), (1, 1, 1))
    rows = [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7]]
    expected = tuple(float(v) for row in rows for v in row)
    for transform in (rows, rows + [[0, 0, 0, 1]], np.array(rows).reshape(-1)):
        assert tuple(fluidcast.Mesh(vertices, indices, transform=transform).c_mesh.transform) == expected
    with pytest.raises(ValueError, match="last row|end with"):
        fluidcast.Mesh(vertices, indices, transform=rows + [[0, 0, 1, 1]])
    with pytest.raises(ValueError, match="3x4"):
        fluidcast.Mesh(vertices, indices, transform=np.eye(3))


@pytest.mark.parametrize("args, error", [
    (dict(vertices=np.zeros((8, 2), np.float32)), ValueError),
    (dict(indices=np.zeros((4, 4), np.uint32)), ValueError),
    (dict(indices=np.zeros(7, np.uint32)), ValueError),
    (dict(indices=np.zeros((12, 3), np.float32)), TypeError),
    (dict(normals=np.zeros((7, 3), np.float32)), ValueError),
    (dict(color=(1, 0)), ValueError),
    (dict(id=-1), ValueError),
])
def test_bad_shapes_and_types_are_refused(args, error):
    vertices, indices = box((0, 0, 0), (1, 1, 1))
    kwargs = dict(vertices=vertices, indices=indices)
    kwargs.update(args)
    with pytest.raises(error):
        fluidcast.Mesh(**kwargs)


def test_negative_indices_are_invalid_values_naming_the_triangle():
    vertices, indices = box((0, 0, 0), (1, 1, 1))
    signed = indices.astype(np.int64)
    signed[5, 1] = -3
    with pytest.raises(fluidcast.Error) as e:
        fluidcast.Mesh(vertices, signed)
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    assert "triangle 5" in e.value.message and "-3" in e.value.message
