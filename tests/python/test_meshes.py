"""Meshes through a real fluidcastd: a box uploaded from numpy hides the ball
behind it (the depth AOV is 0 where the box is, the ball's around it), moves
aside and goes away; a tank's near wall hidden with hide_near; bad meshes refused."""

import ctypes

import numpy as np
import pytest

import fluidcast
from fluidcast import _capi
from helpers import SIZE, ball, box, look_at_ball

W, H = SIZE
CENTRE = (H // 2, W // 2)
# look_at_ball's camera sees the ball (radius 0.5, 4 units away) about 21 pixels
# about the centre; a box 0.2 wide 1.8 units away covers about 9 pixels about it.
RING = (H // 2, W // 2 + 15)    # on the ball, beside the box


def small_box():
    return box((-0.1, -2.0, -0.1), (0.1, -1.8, 0.1))


def depth(client):
    return client.render_image("depth")


def test_a_box_from_numpy_hides_the_ball_behind_it(client, monkeypatch):
    client.send_frame(ball())
    look_at_ball(client)
    plain = depth(client)
    assert plain[CENTRE] > 3 and plain[RING] > 3

    sent = []
    real = _capi.fc_client_upload_mesh

    def spy(handle, mesh_ref, err_ref):
        mesh = mesh_ref._obj
        sent.append((ctypes.cast(mesh.vertices, ctypes.c_void_p).value,
                     ctypes.cast(mesh.indices, ctypes.c_void_p).value))
        return real(handle, mesh_ref, err_ref)

    monkeypatch.setattr(_capi, "fc_client_upload_mesh", spy)
    vertices, indices = small_box()
    mesh = client.upload_mesh(vertices, indices, id=3)
    assert mesh.copied == () and sent == [(vertices.ctypes.data, indices.ctypes.data)]

    hidden = depth(client)
    assert hidden[CENTRE] == 0, "the box hides the fluid: no fluid depth behind it"
    assert hidden[RING] == plain[RING], "beside the box the ball is as before"
    # Every pixel the box covers has depth 0; outside it the image is unchanged.
    changed = hidden != plain
    assert np.all(hidden[changed] == 0)
    rows, cols = np.nonzero(changed)
    assert 10 <= len(rows) and np.ptp(rows) < 25 and np.ptp(cols) < 25, (np.ptp(rows), np.ptp(cols))

    # Moved 5 units aside (a 4x4 matrix): the ball is whole again.
    aside = np.eye(4)
    aside[0, 3] = 5
    client.move_mesh(3, aside)
    np.testing.assert_array_equal(depth(client), plain)
    # Back in front with a 3x4 (R | t), then removed.
    client.move_meshes({3: np.eye(3, 4)})
    assert depth(client)[CENTRE] == 0
    client.remove_mesh(3)
    np.testing.assert_array_equal(depth(client), plain)
    client.remove_mesh(3)          # no such mesh any more: no error


def test_hide_near_shows_the_fluid_inside_a_tank(client):
    client.send_frame(ball())
    look_at_ball(client)
    plain = depth(client)
    vertices, indices = box((-1, -1, -1), (1, 1, 1))     # around the ball
    client.upload_mesh(vertices, indices, id=1)
    assert np.all(depth(client) == 0), "the near wall hides everything"
    client.upload_mesh(vertices, indices, id=1, hide_near=True)   # replaces mesh 1
    np.testing.assert_array_equal(depth(client), plain)


def test_glass_does_not_hide_the_fluid(client):
    client.send_frame(ball())
    look_at_ball(client)
    plain = client.render_image("depth")
    vertices, indices = small_box()
    client.upload_mesh(vertices, indices, opacity=0.3, color=(0.2, 0.4, 1.0))
    glass = client.render_image("depth")
    assert glass[CENTRE] == plain[CENTRE] > 0


def test_bad_indices_raise_invalid_value(client):
    client.send_frame(ball(500))
    look_at_ball(client)
    vertices, indices = small_box()
    bad = indices.copy()
    bad[4, 2] = 8                  # 8 vertices: 0..7
    with pytest.raises(fluidcast.Error) as e:
        client.upload_mesh(vertices, bad)
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    assert "triangle 4" in e.value.message, e.value.message
    signed = indices.astype(np.int32)
    signed[0, 0] = -1
    with pytest.raises(fluidcast.Error) as e:
        client.upload_mesh(vertices, signed)
    assert e.value.code is fluidcast.Code.INVALID_VALUE and "triangle 0" in e.value.message
    with pytest.raises(fluidcast.Error) as e:
        client.upload_mesh(vertices, indices, opacity=1.5)
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    nan = vertices.copy()
    nan[2, 1] = np.nan
    with pytest.raises(fluidcast.Error) as e:
        client.upload_mesh(nan, indices)
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    with pytest.raises(fluidcast.Error) as e:
        client.move_meshes([(1, np.eye(3, 4)), (1, np.eye(3, 4))])
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    # Nothing was sent: the connection renders as before.
    assert client.render_image("depth")[CENTRE] > 0


def test_moving_a_mesh_never_sent_is_reported_by_the_next_render(client):
    client.send_frame(ball(500))
    look_at_ball(client)
    client.move_mesh(99, None)
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.BAD_STATE
    client.render()                # the connection stays usable
