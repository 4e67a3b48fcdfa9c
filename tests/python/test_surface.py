"""Client.mesh through a real fluidcastd (PROTOCOL.md section 13): a ball of
particles comes back as one closed surface with outward normals and the
attributes asked for, the same bytes every time; requests the server must
refuse (before any frame, a grid past its budget) raise their codes and the
connection and daemon go on serving."""

import numpy as np
import pytest

import fluidcast
from fluidcast import Code
from helpers import ball, look_at_ball


def ball_frame(client, count=3000):
    points = ball(count=count, radius=0.5)
    velocity = np.zeros_like(points)
    velocity[:, 0] = points[:, 0] * 2.0           # a linear velocity field
    density = np.full(count, 1000.0, dtype=np.float32)
    ids = np.arange(100, 100 + count, dtype=np.uint32)
    client.send_frame(points, density=density, velocity=velocity, ids=ids)
    return points, ids


def edge_uses(triangles):
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return counts


def test_a_ball_is_one_closed_surface_with_its_attributes(client):
    points, ids = ball_frame(client)
    client.set_settings(radius=0.05)               # about the particles' spacing: one smooth surface
    mesh = client.mesh()
    v, t = len(mesh.positions), len(mesh.triangles)
    assert v > 100 and t > 100
    assert mesh.positions.shape == (v, 3) and mesh.normals.shape == (v, 3) and mesh.triangles.shape == (t, 3)
    assert mesh.positions.dtype == np.float32 and mesh.triangles.dtype == np.uint32
    assert int(mesh.triangles.max()) < v
    assert np.all(edge_uses(mesh.triangles) == 2), "every edge in exactly two triangles"
    # Counter-clockwise seen from outside: a positive enclosed volume, and the vertex normals
    # on the side the windings give (random particles leave bubbles inside: their surfaces
    # face the bubble, so the outer vertices alone are compared with the radial direction).
    a, b, c = (mesh.positions[mesh.triangles[:, k]].astype(np.float64) for k in range(3))
    assert np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6 > 0.2
    faces = np.cross(b - a, c - a)
    at_vertex = np.zeros((v, 3))
    for k in range(3):
        np.add.at(at_vertex, mesh.triangles[:, k], faces)
    assert np.mean(np.einsum("ij,ij->i", at_vertex, mesh.normals) > 0) > 0.95
    radii = np.linalg.norm(mesh.positions, axis=1)
    outer = radii > 0.52          # beyond every particle: on the outer hull
    assert outer.sum() > v / 2
    outward = np.einsum("ij,ij->i", mesh.normals[outer], mesh.positions[outer] / radii[outer, None])
    assert np.mean(outward > 0) > 0.95
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1, atol=1e-3)
    assert mesh.speed.shape == (v,) and mesh.density.shape == (v,) and mesh.velocity.shape == (v, 3)
    assert np.allclose(mesh.density, 1000.0, rtol=1e-3)
    assert np.corrcoef(mesh.velocity[:, 0], mesh.positions[:, 0])[0, 1] > 0.9
    assert set(np.unique(mesh.id)) <= set(ids.tolist())
    assert mesh.extract_ms >= 0


def test_only_the_attributes_asked_for_and_the_same_bytes_each_time(client):
    ball_frame(client)
    plain = client.mesh(attributes=None)
    assert plain.speed is None and plain.density is None and plain.velocity is None and plain.id is None
    speed = client.mesh(attributes=["speed"])
    assert speed.speed is not None and speed.velocity is None and speed.id is None
    again = client.mesh(attributes=None)
    assert np.array_equal(plain.positions, again.positions) and np.array_equal(plain.triangles, again.triangles)
    assert np.array_equal(plain.positions, speed.positions)
    with pytest.raises(ValueError):
        client.mesh(attributes=["colour"])


def test_no_frame_is_bad_state_and_the_connection_goes_on(client):
    with pytest.raises(fluidcast.Error) as refused:
        client.mesh()
    assert refused.value.code == Code.BAD_STATE
    ball_frame(client, count=500)
    assert len(client.mesh(attributes=None).triangles) > 0


def test_a_grid_past_the_budget_is_limit_and_the_daemon_goes_on(client, connect):
    far = ball(count=200, radius=0.5)
    far[::2] += np.float32(5000.0)                 # two clusters 5000 units apart
    client.send_frame(far)
    client.set_settings(radius=0.001, surface_cell=0.3)
    with pytest.raises(fluidcast.Error) as refused:
        client.mesh()
    assert refused.value.code == Code.LIMIT
    client.set_settings(radius=0.0)
    ball_frame(client, count=500)
    assert len(client.mesh(attributes=None).triangles) > 0
    other = connect()
    other.send_frame(ball())
    look_at_ball(other)
    assert other.render("png")[:8] == b"\x89PNG\r\n\x1a\n"
