"""The binding against a real fluidcastd: connect, frames, camera, settings, renders, errors."""

import ctypes
import socket

import numpy as np
import pytest

import fluidcast
from fluidcast import _capi
from helpers import SIZE, TINTED_LOOK_ABSORPTION, ball, look_at_ball, png_size


def test_connect_and_server_info(client):
    info = client.server_info
    assert info.server_version.startswith("fluidcastd")
    assert info.protocol_version == 1
    assert info.max_width >= SIZE[0] and info.max_height >= SIZE[1]
    assert info.capabilities & fluidcast.SERVER_CAN_STREAM
    # The daemon names its GPU device (capability DEVICE): llvmpipe here, an EGL device on a GPU.
    assert info.capabilities & fluidcast.SERVER_CAN_DEVICE
    assert info.device == "Mesa surfaceless platform (no device)" or info.device.startswith("EGL device ")
    assert not client.closed


def test_connect_with_a_session_on_a_plain_address(daemon):
    """A session places "srv:" connections only; a plain address is used as given."""
    with fluidcast.connect(daemon.address, session="dam") as c:
        assert c.daemon == daemon.address and c.address == daemon.address


def test_connect_errors():
    with pytest.raises(fluidcast.Error) as e:
        fluidcast.connect("localhost:99999")
    assert e.value.code == fluidcast.Code.USAGE and "port" in e.value.message
    with socket.socket() as s:          # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(fluidcast.Error) as e:
        fluidcast.connect("127.0.0.1:%d" % port, connect_timeout=5)
    assert e.value.code == fluidcast.Code.CONNECT
    with pytest.raises(fluidcast.Error) as e:
        fluidcast.connect("srv:", session="dam")
    assert e.value.code == fluidcast.Code.USAGE and "SRV" in e.value.message


def test_render_png_has_the_camera_size(client):
    client.send_frame(ball())
    look_at_ball(client, size=(200, 150))
    data = client.render()
    assert png_size(data) == (200, 150)
    result = client.render_result(format="jpeg", quality=80)
    assert result.data[:3] == b"\xff\xd8\xff" and (result.width, result.height) == (200, 150)
    assert result.format is fluidcast.Format.JPEG and result.aov is fluidcast.Aov.COLOR
    assert fluidcast.Stage.TOTAL in result.stage_ms and result.stage_ms[fluidcast.Stage.TOTAL] > 0


def test_render_image_colour_shows_the_fluid_where_the_particles_are(client):
    client.send_frame(ball())
    look_at_ball(client)
    client.set_settings(absorption=TINTED_LOOK_ABSORPTION)
    image = client.render_image()
    w, h = SIZE
    assert image.shape == (h, w, 4) and image.dtype == np.uint8
    centre = image[h // 2, w // 2].astype(int)
    corner = image[2, 2].astype(int)
    assert np.abs(centre - corner)[:3].sum() > 30, (centre, corner)

    # The same view with the ball moved out of it: the centre is background like the corner.
    client.send_frame(ball(centre=(0, 0, 50)))
    empty = client.render_image()
    assert np.abs(empty[h // 2, w // 2].astype(int) - centre)[:3].sum() > 30
    np.testing.assert_array_equal(empty[2, 2], image[2, 2])


def test_render_image_aovs(client):
    client.send_frame(ball())
    look_at_ball(client)
    w, h = SIZE
    depth = client.render_image("depth")
    assert depth.shape == (h, w) and depth.dtype == np.float32
    # The ball's near side is 4 - 0.5 away, and no fluid (0) in the corner.
    assert 3.3 < depth[h // 2, w // 2] < 4.0 and depth[0, 0] == 0
    normal = client.render_image(fluidcast.Aov.NORMAL)
    assert normal.shape == (h, w, 3) and normal.dtype == np.float32
    assert np.linalg.norm(normal[h // 2, w // 2]) == pytest.approx(1, abs=0.05)
    raw = client.render_result(format="raw", aov="thickness")
    assert raw.format is fluidcast.Format.RAW and len(raw.data) == w * h * 4
    assert raw.to_array().shape == (h, w)


def test_send_frame_passes_the_callers_array_without_a_copy(client, monkeypatch):
    """The fc_frame libfluidcast gets points into the caller's float32 array; float64 goes through a copy."""
    sent = []
    real = _capi.fc_client_send_frame

    def spy(handle, frame_ref, err_ref):
        frame = frame_ref._obj
        sent.append((frame.count, ctypes.cast(frame.positions, ctypes.c_void_p).value,
                     ctypes.cast(frame.density, ctypes.c_void_p).value))
        return real(handle, frame_ref, err_ref)

    monkeypatch.setattr(_capi, "fc_client_send_frame", spy)
    positions = ball(3000)
    density = np.full(3000, 1000, np.float32)
    frame = client.send_frame(positions, density=density)
    assert frame.copied == ()
    assert sent[-1] == (3000, positions.ctypes.data, density.ctypes.data)

    p64 = positions.astype(np.float64)
    frame = client.send_frame(p64)
    assert frame.copied == ("positions",)
    assert sent[-1][1] == frame.positions.ctypes.data != p64.ctypes.data
    look_at_ball(client)
    assert png_size(client.render()) == SIZE   # the frames went through


def test_nan_position_raises_invalid_value_with_the_servers_message(client):
    positions = ball(500)
    positions[123, 1] = np.nan
    client.send_frame(positions)      # the server answers only at the next render
    look_at_ball(client)
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    assert e.value.message.startswith("server: ") and "particle 123" in e.value.message
    # A server error leaves the connection usable.
    client.send_frame(ball(500))
    assert png_size(client.render()) == SIZE


def test_per_particle_radius_out_of_domain_names_the_particle(client):
    radius = np.full(500, 0.05, np.float32)
    radius[77] = 0.0
    client.send_frame(ball(500), radius=radius)
    look_at_ball(client)
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    assert "particle 77 has radius 0, outside (0, 1e6]" in e.value.message
    radius[77] = 0.05
    client.send_frame(ball(500), radius=radius)
    assert png_size(client.render()) == SIZE


def test_per_particle_radii_through_the_daemon(client):
    # Two particles 4 units in front of the eye, radii 0.2 and 0.5: with the
    # radius setting 0 (auto) the depth at each centre is 4 - r_i; a setting
    # > 0 overrides both.
    positions = np.array([[-0.6, 0, 0], [0.6, 0, 0]], np.float32)
    radius = np.array([0.2, 0.5], np.float32)
    client.send_frame(positions, radius=radius)
    client.set_camera(eye=(0, -4, 0), target=(0, 0, 0), up=(0, 0, 1), fov=40, size=(161, 81))
    client.set_settings(radius=0, smoothing="none")
    depth = client.render_image("depth")
    f = 0.5 * 81 / np.tan(np.radians(20))          # pixels per unit of x / depth
    columns = [int(80 + x * f / 4) for x in (-0.6, 0.6)]
    for column, r in zip(columns, radius):
        assert abs(depth[40, column] - (4 - r)) < 0.01, (column, depth[40, column], 4 - r)
    # The silhouettes' widths follow the radii: about 2 r f / 4 pixels each.
    widths = [int(np.count_nonzero(depth[40, :80] > 0)), int(np.count_nonzero(depth[40, 81:] > 0))]
    for width, r in zip(widths, radius):
        assert abs(width - 2 * r * f / 4) <= 2.5, (widths, r)
    client.set_settings(radius=0.3)
    depth = client.render_image("depth")
    for column in columns:
        assert abs(depth[40, column] - (4 - 0.3)) < 0.01


def test_negative_radius_raises_invalid_value(client):
    client.send_frame(ball(500))
    look_at_ball(client)
    client.set_settings(radius=-1)
    assert client.settings["radius"] == -1
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    assert e.value.message.startswith("server: ") and "radius" in e.value.message
    client.set_settings(radius=0.05)
    assert png_size(client.render()) == SIZE


def test_settings(client):
    defaults = fluidcast.default_settings()
    assert tuple(defaults) == fluidcast.SETTING_NAMES
    assert client.settings == defaults
    client.set_settings(smoothing="bilateral", iterations=3, fluid_color=(0.5, 0.1, 0.1), kernel="anisotropic",
                        color_by=fluidcast.ColorBy.DENSITY, colormap="turbo", color_range=(900, 1100), shadow=0)
    s = client.settings
    assert s["smoothing"] is fluidcast.Smoothing.BILATERAL and s["kernel"] is fluidcast.Kernel.ANISOTROPIC
    assert s["colormap"] is fluidcast.Colormap.TURBO and s["color_range"] == (900, 1100)
    assert s["fluid_color"] == pytest.approx((0.5, 0.1, 0.1)) and s["iterations"] == 3 and s["shadow"] == 0
    before = client.settings
    with pytest.raises(TypeError, match="no field 'radious'"):
        client.set_settings(radius=0.1, radious=0.1)
    with pytest.raises(ValueError):
        client.set_settings(smoothing="blurry")
    with pytest.raises(ValueError):
        client.set_settings(fluid_color=(1, 2))
    with pytest.raises(ValueError):
        client.set_settings(iterations=-1)
    assert client.settings == before     # nothing applied by a refused call
    # The accepted ones render: density colouring needs densities.
    client.send_frame(ball(1000), density=np.linspace(900, 1100, 1000, dtype=np.float32))
    look_at_ball(client)
    assert client.render_image().shape == (SIZE[1], SIZE[0], 4)


def test_bad_requests_are_refused_before_sending(client):
    with pytest.raises(ValueError):
        client.render(format="gif")
    with pytest.raises(ValueError):
        client.render(aov="albedo")
    with pytest.raises(ValueError):
        client.set_camera((0, 0, 1), (0, 0, 0), size=(-1, 10))
    with pytest.raises(ValueError):
        client.set_camera((0, 0), (0, 0, 0))
    with pytest.raises(fluidcast.Error) as e:       # C's check: an empty frame
        client.send_frame(np.zeros((0, 3), np.float32))
    assert e.value.code is fluidcast.Code.USAGE


def test_server_side_request_errors(client):
    with pytest.raises(fluidcast.Error) as e:       # no frame yet
        client.render()
    assert e.value.code is fluidcast.Code.BAD_STATE
    client.send_frame(ball(200))
    client.set_camera(eye=(0, 0, 0), target=(0, 0, 0), size=SIZE)
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    look_at_ball(client)
    with pytest.raises(fluidcast.Error) as e:       # PNG holds colour only
        client.render(format="png", aov="depth")
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    client.set_background(b"not an image")
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.INVALID_VALUE
    client.set_background(None)
    assert png_size(client.render()) == SIZE


def test_background_image(client, tmp_path):
    client.send_frame(ball(500))
    look_at_ball(client)
    plain = client.render_image()
    background = client.render("png")   # any PNG will do as a background
    client.set_background(background)
    with_bytes = client.render_image()
    path = tmp_path / "background.png"
    path.write_bytes(background)
    client.set_background(str(path))
    with_file = client.render_image()
    np.testing.assert_array_equal(with_bytes, with_file)
    assert (with_bytes != plain).any()
    with pytest.raises(fluidcast.Error) as e:
        client.set_background(str(tmp_path / "missing.png"))
    assert e.value.code is fluidcast.Code.IO


def test_environment_cube_map(client, tmp_path):
    client.send_frame(ball(500))
    client.set_camera(eye=(0, -4, 0), target=(0, 0, 0), size=(32, 32))
    face = client.render("png")           # a square PNG serves as every face
    look_at_ball(client)
    plain = client.render_image()
    client.set_environment([face] * 6)
    with_bytes = client.render_image()
    assert (with_bytes != plain).any()      # reflected in the fluid instead of the procedural sky
    paths = []
    for i in range(6):
        paths.append(tmp_path / ("face%d.png" % i))
        paths[-1].write_bytes(face)
    client.set_environment([str(p) for p in paths])
    np.testing.assert_array_equal(client.render_image(), with_bytes)
    client.set_environment(None)
    np.testing.assert_array_equal(client.render_image(), plain)
    with pytest.raises(ValueError):
        client.set_environment([face] * 5)
    look_at_ball(client, size=(40, 30))
    client.set_environment([client.render("png")] * 6)     # not square: the server refuses it
    with pytest.raises(fluidcast.Error) as e:
        client.render()
    assert e.value.code is fluidcast.Code.INVALID_VALUE


def test_close(connect):
    c = connect()
    with c:
        c.send_frame(ball(10))
    assert c.closed
    with pytest.raises(fluidcast.Error) as e:
        c.send_frame(ball(10))
    assert e.value.code is fluidcast.Code.CLOSED
    c.close()   # again: nothing
