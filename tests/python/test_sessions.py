"""Named sessions through the binding: publish, subscribe, stream images, encoded uploads, chunks."""

import time

import numpy as np
import pytest

import fluidcast
from helpers import SIZE, ball, look_at_ball, png_size


def next_frame_image(viewer, frame_number):
    """The viewer's next image of frame ``frame_number`` (skipping re-renders of earlier frames)."""
    for _ in range(10):
        image = viewer.next_image()
        assert not image.ended
        if image.frame_number == frame_number:
            return image
    pytest.fail("no image of frame %d" % frame_number)


def test_publish_subscribe_round_trip(connect):
    producer, viewer = connect(name="pytest-producer"), connect(name="pytest-viewer")
    status = producer.publish("py-round-trip")
    assert status.name == "py-round-trip" and status.producers == 1 and status.frames == 0
    status = viewer.subscribe("py-round-trip", format="png", size=SIZE)
    assert status.viewers == 1
    listed = {s.name: s for s in producer.list_sessions()}
    assert listed["py-round-trip"].producers == 1 and listed["py-round-trip"].viewers == 1

    producer.send_frame(ball())
    image = next_frame_image(viewer, 1)
    assert isinstance(image, fluidcast.StreamImage)
    assert png_size(image.data) == SIZE and image.format is fluidcast.Format.PNG
    assert image.sequence == 1 and image.missed == 0 and not image.refresh

    # The viewer's own camera re-renders the current frame.
    look_at_ball(viewer, size=(120, 90))
    image = viewer.next_image()
    assert image.view_change and image.frame_number == 1 and png_size(image.data) == (120, 90)

    producer.leave_session()
    ended = viewer.next_image()
    assert ended.ended and ended.data == b"" and viewer.session_ended
    with pytest.raises(fluidcast.Error) as e:
        producer.leave_session()
    assert e.value.code is fluidcast.Code.BAD_STATE

    # The ended session keeps its last frame for the viewer: its camera still re-renders it.
    viewer.set_camera(eye=(0, -6, 0), target=(0, 0, 0), up=(0, 0, 1), fov=40, size=(120, 90))
    again = viewer.next_image()
    assert again.view_change and again.frame_number == 1 and png_size(again.data) == (120, 90)
    assert again.data != image.data
    viewer.leave_session()
    assert not viewer.session_ended
    assert "py-round-trip" not in {s.name for s in producer.list_sessions()}


def _nal_types(data):
    """The NAL unit types of an Annex B access unit."""
    return {data[i + 3] & 0x1F for i in range(len(data) - 3) if data[i:i + 3] == b"\x00\x00\x01"}


def test_h264_stream(connect):
    producer, viewer = connect(), connect()
    producer.publish("py-h264")
    viewer.subscribe("py-h264", format="h264", size=(64, 48))
    producer.send_frame(ball())
    first = next_frame_image(viewer, 1)
    assert not first.refresh and first.format is fluidcast.Format.H264 and (first.width, first.height) == (64, 48)
    assert first.keyframe and {7, 8, 5} <= _nal_types(first.data)
    producer.send_frame(ball() * 1.1)
    second = next_frame_image(viewer, 2)
    assert not second.keyframe and 5 not in _nal_types(second.data)
    viewer.request_keyframe()
    again = viewer.next_image()
    while again.refresh:   # a lossless PNG refresh may come first on a slow machine
        again = viewer.next_image()
    assert again.view_change and again.keyframe and again.frame_number == 2 and 5 in _nal_types(again.data)
    with pytest.raises(fluidcast.Error) as e:   # 4:2:0 needs even sides
        connect().subscribe("py-h264", format="h264", size=(63, 48))
    assert e.value.code is fluidcast.Code.INVALID_VALUE


def test_raw_stream_and_encoded_uploads(connect):
    producer, viewer = connect(), connect()
    info = producer.server_info
    producer.publish("py-uploads")
    viewer.subscribe("py-uploads", format="raw", size=SIZE)
    # A regular grid: zstd finds it compressible, 16-bit positions halve it.
    grid = np.stack(np.meshgrid(*[np.linspace(-0.5, 0.5, 16, dtype=np.float32)] * 3, indexing="ij"), -1)
    grid = np.ascontiguousarray(grid.reshape(-1, 3))
    number = 0
    for zstd, quantize in ((False, False), (True, False), (False, True), (True, True)):
        if (zstd and not info.capabilities & fluidcast.SERVER_CAN_ZSTD) or \
                (quantize and not info.capabilities & fluidcast.SERVER_CAN_QUANTIZE16):
            continue
        stats = producer.upload_frame(grid, zstd=zstd, quantize16=quantize)
        number += 1
        assert stats.raw_bytes >= len(grid) * 12
        if zstd or quantize:
            assert stats.wire_bytes < stats.raw_bytes, (zstd, quantize, stats)
        image = next_frame_image(viewer, number)
        pixels = image.to_array()
        assert pixels.shape == (SIZE[1], SIZE[0], 4) and pixels.dtype == np.uint8
        centre, corner = pixels[SIZE[1] // 2, SIZE[0] // 2].astype(int), pixels[1, 1].astype(int)
        assert np.abs(centre - corner)[:3].sum() > 30
    assert number >= 1
    bad = grid.copy()
    bad[5, 0] = np.inf
    if info.capabilities & fluidcast.SERVER_CAN_QUANTIZE16:
        with pytest.raises(fluidcast.Error) as e:   # libfluidcast's own check, nothing sent
            producer.upload_frame(bad, quantize16=True)
        assert e.value.code is fluidcast.Code.USAGE


def test_chunks_of_two_ranks_and_poll_errors(connect):
    ranks = [connect(name="rank0"), connect(name="rank1")]
    viewer = connect()
    for rank in ranks:
        rank.publish("py-ranks")
    viewer.subscribe("py-ranks", format="png", size=SIZE)
    whole = ball(2000)
    ranks[0].send_chunk(1, 0, 2, whole[:1000])
    ranks[1].send_chunk(1, 1, 2, whole[1000:], zstd=bool(ranks[1].server_info.capabilities
                                                          & fluidcast.SERVER_CAN_ZSTD))
    image = next_frame_image(viewer, 1)
    assert png_size(image.data) == SIZE

    ranks[0].send_chunk(2, 5, 2, whole[:10])       # index >= count: rejected, reported later
    deadline = time.monotonic() + 20
    with pytest.raises(fluidcast.Error) as e:
        while time.monotonic() < deadline:
            ranks[0].poll_errors()
            time.sleep(0.05)
    assert e.value.code is fluidcast.Code.INVALID_VALUE and e.value.message.startswith("server: ")
    ranks[0].poll_errors()                          # reported once; the connection stays usable


def test_session_errors(connect):
    c = connect()
    with pytest.raises(fluidcast.Error) as e:
        c.next_image()
    assert e.value.code is fluidcast.Code.USAGE
    with pytest.raises(fluidcast.Error) as e:
        c.publish("x" * 65)
    assert e.value.code in (fluidcast.Code.USAGE, fluidcast.Code.INVALID_VALUE)
    c.publish("py-errors")
    with pytest.raises(fluidcast.Error) as e:
        c.subscribe("py-errors")
    assert e.value.code is fluidcast.Code.BAD_STATE
