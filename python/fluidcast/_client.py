"""Client: one connection to a fluidcastd, every fluidcast.h call as a method."""

import ctypes
import math
import os
import threading
from typing import NamedTuple

import numpy as np

from . import _capi
from ._capi import (FcCamera, FcConnectOptions, FcError, FcImageResult, FcRenderRequest, FcServerInfo, FcSessionStatus,
                    FcSettings, FcStreamImage, FcSurfaceMesh, FcUploadOptions, FcUploadStats)
from ._enums import (Aov, Code, ColorBy, Colormap, Format, JpegSubsampling, Kernel, Smoothing, Stage, SurfaceKernel,
                     SurfaceMode, UPLOAD_QUANTIZE16, UPLOAD_ZSTD,
                     parse)
from ._errors import Error, raise_for
from ._frame import as_frame
from ._mesh import as_mesh, transform_entries
from ._surface import attribute_bits, from_c as surface_from_c

_UINT32_MAX = 0xFFFFFFFF


# ---- plain results --------------------------------------------------------

class ServerInfo(NamedTuple):
    """fc_server_info: what the server announced when the connection opened."""
    protocol_version: int
    server_version: str   #: e.g. "fluidcastd 0.1.0"
    renderer: str         #: the daemon's GL_RENDERER
    max_particles: int    #: largest frame the server accepts
    max_width: int        #: largest image the server renders
    max_height: int
    max_message: int      #: largest message payload, in bytes, the server reads
    capabilities: int     #: SERVER_CAN_* bits granted to this connection
    device: str = ""      #: the daemon's GPU device ("" from a server without SERVER_CAN_DEVICE)


class SessionStatus(NamedTuple):
    """fc_session_status: a named session's state."""
    name: str
    producers: int        #: connections publishing to it
    viewers: int          #: connections subscribed to it
    frames: int           #: complete frames published so far
    last_frame: int       #: frame number of the newest, 0 = none yet


class UploadStats(NamedTuple):
    """fc_upload_stats: what one upload cost."""
    raw_bytes: int        #: bytes the frame takes as a plain, uncompressed message
    wire_bytes: int       #: bytes actually sent


def _raw_layout(size, width, height, aov):
    """(dtype, shape) of a RAW image of ``size`` bytes, as PROTOCOL.md lays it out.

    Rows top to bottom, tightly packed: RGBA8 for the colour AOV -> (H, W, 4)
    uint8; little-endian float32 channels for the others -> (H, W) for one
    channel, (H, W, 3) for the normal AOV. Error(PROTOCOL) when the size does
    not fit.
    """
    pixels = width * height
    if aov == Aov.COLOR:
        dtype, channels = np.dtype(np.uint8), 4
    else:
        dtype = np.dtype("<f4")
        channels = size // (pixels * 4) if pixels else 0
    if pixels == 0 or channels not in (1, 3, 4) or size != pixels * channels * dtype.itemsize:
        raise Error(Code.PROTOCOL, "a RAW %s image of %dx%d cannot be %d bytes" % (_name(aov), width, height, size))
    return dtype, (height, width) if channels == 1 else (height, width, channels)


def _raw_to_array(address, size, width, height, aov):
    """Copies a RAW image (``size`` bytes at ``address``) into a new numpy array (float32 or uint8)."""
    dtype, shape = _raw_layout(size, width, height, aov)
    array = np.empty(shape, dtype)
    ctypes.memmove(array.ctypes.data, address, size)
    return array.astype(np.float32, copy=False) if dtype.kind == "f" else array


class Image:
    """An image the server rendered (fc_image_result), its bytes copied out of libfluidcast.

    Attributes: ``data`` (bytes: a complete PNG, JPEG or EXR file, or RAW pixel
    rows), ``width``, ``height``, ``format`` (:class:`Format`), ``aov``
    (:class:`Aov`), ``stage_ms`` ({:class:`Stage`: server milliseconds} for the
    stages the server measured).
    """

    def __init__(self, result):
        self.width = result.width
        self.height = result.height
        self.format = _enum_or_int(Format, result.format)
        self.aov = _enum_or_int(Aov, result.aov)
        self.stage_ms = {Stage(i): ms for i, ms in enumerate(result.stage_ms) if ms >= 0 and i < len(Stage)}
        self.data = ctypes.string_at(result.data, result.size) if result.size else b""

    def to_array(self):
        """The pixels as a new numpy array; RAW images only (see :meth:`Client.render_image`)."""
        if self.format != Format.RAW:
            raise ValueError("to_array needs a RAW image, this one is %s" % getattr(self.format, "name", self.format))
        dtype, shape = _raw_layout(len(self.data), self.width, self.height, self.aov)
        array = np.frombuffer(self.data, dtype).reshape(shape)
        return array.astype(np.float32 if dtype.kind == "f" else np.uint8)   # a writable copy

    def __repr__(self):
        return "<fluidcast.Image %dx%d %s %s, %d bytes>" % (self.width, self.height, _name(self.format),
                                                          _name(self.aov), len(self.data))


class StreamImage(Image):
    """One image of a subscribed session (fc_stream_image).

    Besides :class:`Image`'s attributes: ``frame_number`` (the producer's
    number of the frame shown), ``sequence`` (1-based count of frames the
    session published up to this one), ``missed`` (frames published since this
    viewer's previous image that it never got), ``refresh`` (a lossless copy of
    a frame already shown lossy), ``view_change`` (the same frame again after
    this viewer's camera or settings changed), ``keyframe`` (H.264: the access
    unit is an IDR frame, where a decoder may start) and ``ended`` (the session
    is over: no image in this one; the viewer stays on the last frame, and only
    its own camera or settings changes make further images, ``view_change``).
    """

    def __init__(self, stream):
        super().__init__(stream.image)
        self.frame_number = stream.frame_number
        self.sequence = stream.sequence
        self.missed = stream.missed
        self.refresh = bool(stream.refresh)
        self.view_change = bool(stream.view_change)
        self.ended = bool(stream.ended)
        self.keyframe = bool(stream.keyframe)

    def __repr__(self):
        if self.ended:
            return "<fluidcast.StreamImage: session ended>"
        return "<fluidcast.StreamImage frame %d, %dx%d %s, %d bytes>" % (self.frame_number, self.width, self.height,
                                                                        _name(self.format), len(self.data))


def _name(value):
    return value.name.lower() if hasattr(value, "name") else str(value)


def _enum_or_int(enum_type, value):
    try:
        return enum_type(value)
    except ValueError:
        return value


def _uint32(what, value):
    value = int(value)
    if not 0 <= value <= _UINT32_MAX:
        raise ValueError("%s: %d does not fit uint32" % (what, value))
    return value


def _vec3(what, value):
    values = tuple(float(v) for v in value)
    if len(values) != 3:
        raise ValueError("%s: expected 3 numbers, got %d" % (what, len(values)))
    return values


def _size(what, size):
    try:
        width, height = size
    except (TypeError, ValueError):
        raise ValueError("%s: expected (width, height), got %r" % (what, size)) from None
    return _uint32(what + " width", width), _uint32(what + " height", height)


def _ms(what, seconds):
    if seconds is None:
        return 0
    ms = int(math.ceil(float(seconds) * 1000))
    if not 1 <= ms <= _UINT32_MAX:
        raise ValueError("%s: %r s is out of range" % (what, seconds))
    return ms


def _request(format, quality, aov):
    return FcRenderRequest(parse(Format, format, "format"), _uint32("quality", quality), parse(Aov, aov, "aov"))


# ---- settings -------------------------------------------------------------

_SETTING_ENUMS = {"smoothing": Smoothing, "kernel": Kernel, "color_by": ColorBy, "colormap": Colormap,
                  "jpeg_subsampling": JpegSubsampling, "surface": SurfaceMode, "surface_kernel": SurfaceKernel}
#: fc_settings' field names, in the header's order.
SETTING_NAMES = tuple(name for name, _ in FcSettings._fields_)
def _default_c_settings():
    settings = FcSettings()
    _capi.fc_settings_default(settings)
    return settings


def _settings_dict(settings):
    out = {}
    for name, ctype in FcSettings._fields_:
        value = getattr(settings, name)
        if name in _SETTING_ENUMS:
            value = _enum_or_int(_SETTING_ENUMS[name], value)
        elif isinstance(value, ctypes.Array):
            value = tuple(value)
        out[name] = value
    return out


def _apply_settings(settings, values):
    """Writes values into an FcSettings; TypeError for a name fc_settings lacks."""
    types = dict(FcSettings._fields_)
    for name, value in values.items():
        ctype = types.get(name)
        if ctype is None:
            raise TypeError("set_settings: fc_settings has no field %r (fields: %s)" % (name, ", ".join(SETTING_NAMES)))
        if name in _SETTING_ENUMS:
            value = parse(_SETTING_ENUMS[name], value, name)
        elif issubclass(ctype, ctypes.Array):
            values_n = tuple(float(v) for v in value)
            if len(values_n) != ctype._length_:
                raise ValueError("%s: expected %d numbers, got %d" % (name, ctype._length_, len(values_n)))
            value = ctype(*values_n)
        elif ctype is ctypes.c_float:
            value = float(value)
        elif ctype is ctypes.c_uint32:
            if isinstance(value, float) and not value.is_integer():
                raise ValueError("%s: expected an integer, got %r" % (name, value))
            value = _uint32(name, value)
        else:
            value = int(value)
        setattr(settings, name, value)


def default_settings():
    """fc_settings_default() as a dict of the fields of fc_settings ("convincing water")."""
    return _settings_dict(_default_c_settings())


# ---- the client -----------------------------------------------------------

def connect(address, token=None, name="fluidcast-python", connect_timeout=None, reply_timeout=None, session=None,
            tls=False, tls_ca=None, tls_cert=None, tls_key=None):
    """Connects to a fluidcastd and returns a :class:`Client` (fc_client_connect_session).

    Arguments:
        address: "HOST:PORT", "HOST" (port 7450), "[IPV6]:PORT", "[IPV6]",
            "unix:PATH", or "srv:NAME" for one of the daemons named by the DNS
            SRV records of NAME (e.g. "srv:_fluidcast._tcp.render.example.org";
            a Kubernetes headless Service provides them).
        token: the daemon's shared secret (fluidcastd --token-file / $FLUIDCAST_TOKEN), or None.
        name: shown in the server's log (truncated to 63 bytes).
        connect_timeout: seconds to reach the server and get its WELCOME; None: 10.
        reply_timeout: longest silence, in seconds, tolerated while sending or
            waiting for a reply (a render can take seconds); None: wait indefinitely.
        session: with a "srv:" address, the name of the session this client
            will publish or subscribe to. Every client of one session computes
            the same order of the SRV targets from the name alone (rendezvous
            hashing, fluidcast.h), so a session's producers and viewers meet on
            one daemon without a router; an unreachable target gives way to the
            next in that order. Without it a "srv:" address picks by the SRV
            priorities and weights (RFC 2782). Other addresses ignore it.
            The records are looked up at each connect, from the DNS servers of
            /etc/resolv.conf or the one $FLUIDCAST_DNS_SERVER ("ADDR[:PORT]") names.
        tls: True for TLS, as an address "tls://HOST:PORT" or "tls://srv:NAME"
            asks for it too (not for "unix:" addresses). The server's
            certificate must chain to tls_ca's CAs (or the system's) and name
            the host connected to.
        tls_ca: a PEM file of the CAs to trust instead of the system's.
        tls_cert, tls_key: a client certificate and its key (PEM; the key may
            be in tls_cert's file), for a daemon that wants one (mutual TLS).

    :attr:`Client.daemon` says which daemon was reached.

    Raises :class:`Error`: ``Code.USAGE`` for a malformed address (or "srv:"
    without a name, a malformed $FLUIDCAST_DNS_SERVER), ``Code.CONNECT`` when
    the server cannot be reached in time (for "srv:": no SRV records, no DNS
    answer, or no target reachable), ``Code.UNAUTHORIZED`` for a missing or
    wrong token, ``Code.VERSION`` and the connection errors when the handshake
    fails, ``Code.PROTOCOL`` for a DNS answer that does not parse; with TLS
    ``Code.TLS_UNKNOWN_CA``, ``TLS_NAME_MISMATCH``, ``TLS_EXPIRED``,
    ``TLS_PLAINTEXT_PEER``, ``TLS_CLIENT_CERT`` or ``TLS`` naming the cause, and
    without it ``Code.TLS_REQUIRED`` from a daemon that wants TLS.
    """
    return Client(address, token=token, name=name, connect_timeout=connect_timeout, reply_timeout=reply_timeout,
                  session=session, tls=tls, tls_ca=tls_ca, tls_cert=tls_cert, tls_key=tls_key)


class Client:
    """An open connection to one fluidcastd (fc_client). Use :func:`connect`.

    A context manager: ``with fluidcast.connect(addr) as c: ...`` closes it on
    exit. Every method blocks until its bytes are sent (and, for those that
    wait for an answer, until it arrived) and raises :class:`Error` when the
    call fails. Requests the server answers only when it rejects them
    (:meth:`send_frame`, :meth:`set_camera`, :meth:`set_settings`, scene
    images, meshes) report that rejection from the next :meth:`render`.

    Like fc_client, one connection serves one thing at a time: calls from
    several threads are serialised by a lock (a thread waiting in
    :meth:`next_image` holds the others until an image arrives); use one client
    per thread for concurrency. ctypes releases the GIL during each call.
    """

    def __init__(self, address, token=None, name="fluidcast-python", connect_timeout=None, reply_timeout=None,
                 session=None, tls=False, tls_ca=None, tls_cert=None, tls_key=None):
        self._handle = None
        self._lock = threading.Lock()
        options = FcConnectOptions(
            name.encode() if name is not None else None,
            _ms("connect_timeout", connect_timeout),
            _ms("reply_timeout", reply_timeout),
            token.encode() if token else None,
            1 if tls else 0,
            *(os.fsencode(path) if path is not None else None for path in (tls_ca, tls_cert, tls_key)))
        handle = _capi.c_client_p()
        err = FcError()
        code = _capi.fc_client_connect_session(os.fsencode(address), session.encode() if session else None,
                                               ctypes.byref(options), ctypes.byref(handle), ctypes.byref(err))
        raise_for(code, err)
        self._handle = handle
        #: the address given to :func:`connect` (e.g. "srv:NAME")
        self.address = address
        #: the session name given to :func:`connect`, or None
        self.session = session or None
        #: the daemon connected to: "HOST:PORT" (for "srv:" addresses the chosen target) or "unix:PATH"
        self.daemon = os.fsdecode(_capi.fc_client_address(self._handle))
        self._settings = _default_c_settings()
        info = FcServerInfo()
        _capi.fc_client_server_info(self._handle, ctypes.byref(info))
        #: :class:`ServerInfo` the server announced at connect time
        self.server_info = ServerInfo(info.protocol_version, info.server_version.decode("utf-8", "replace"),
                                      info.renderer.decode("utf-8", "replace"), info.max_particles, info.max_width,
                                      info.max_height, info.max_message, info.capabilities,
                                      info.device.decode("utf-8", "replace"))

    # -- lifetime --

    def close(self):
        """Says GOODBYE (best effort), closes the connection (fc_client_close). Calling it again does nothing."""
        with self._lock:
            handle, self._handle = self._handle, None
            if handle:
                _capi.fc_client_close(handle)

    @property
    def closed(self):
        """True once :meth:`close` was called."""
        return not self._handle

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_handle", None):
            try:
                self.close()
            except Exception:
                pass

    def __repr__(self):
        return "<fluidcast.Client %s%s>" % (self.address if hasattr(self, "address") else "?",
                                             " closed" if self.closed else "")

    def _call(self, function, *args):
        """Calls an fc_client_* function with the handle first and an fc_error last; raises on failure."""
        err = FcError()
        with self._lock:
            if not self._handle:
                raise Error(Code.CLOSED, "the client is closed")
            code = function(self._handle, *args, ctypes.byref(err))
        raise_for(code, err)

    # -- frame, camera, settings --

    def send_frame(self, positions, density=None, velocity=None, ids=None, radius=None):
        """Sends a particle frame; it replaces the previous one (fc_client_send_frame).

        Arguments are numpy arrays (see :class:`Frame`): positions (N, 3)
        float32, density (N,) float32, velocity (N, 3) float32, ids (N,)
        uint32, radius (N,) float32 per-particle splat radii in world units
        (each finite, > 0 and <= 1e6; a settings ``radius`` > 0 overrides
        them), the optional ones None when absent; or a prepared
        :class:`Frame` as ``positions``. Arrays that already are C-contiguous
        float32 (uint32 for ids) are sent from where they are, without a copy;
        others (float64, strided views) are converted to a copy first.

        The server answers only a rejection (non-finite values, too many
        particles, a radius outside (0, 1e6]), reported by the next :meth:`render`. Raises
        :class:`Error`: ``Code.TOO_LARGE`` (nothing sent) beyond the server's
        message limit, ``Code.USAGE`` for an empty frame, connection errors.
        Returns the :class:`Frame` that was sent (its ``copied`` says what was
        converted).
        """
        frame = as_frame(positions, density, velocity, ids, radius)
        self._call(_capi.fc_client_send_frame, ctypes.byref(frame.c_frame))
        return frame

    def set_camera(self, eye, target, up=(0, 0, 1), fov=40, size=(1280, 720)):
        """Sends the camera for the following renders (fc_client_set_camera).

        A right-handed look-at camera: ``eye`` looks at ``target`` with ``up``
        upwards; ``fov`` is the vertical field of view in degrees, in (0, 180);
        ``size`` the image's (width, height) in pixels. A rejection (eye ==
        target, up parallel to the view, a size beyond the server's) is
        reported by the next :meth:`render`.
        """
        width, height = _size("size", size)
        camera = FcCamera(_vec3("eye", eye), _vec3("target", target), _vec3("up", up), float(fov), width, height)
        self._call(_capi.fc_client_set_camera, ctypes.byref(camera))

    def set_settings(self, **fields):
        """Sends render settings (fc_client_set_settings), changing the fields named.

        Keyword names are fc_settings' fields (``SETTING_NAMES``): radius,
        smoothing, iterations, filter_radius, smooth_scale, fluid_color,
        absorption, ior, refraction, specular, shininess, thickness_scale,
        thickness_blur, noise, foam, foam_tau, foam_decay, density_threshold,
        kernel, shadow, exposure, color_by, colormap, color_range,
        jpeg_subsampling, surface, surface_cell, surface_kernel, surface_smoothing,
        contact_shadow, depth_dimming, aerated_foam (see
        fluidcast_types.h for each one's meaning and domain). ``smoothing``,
        ``kernel``, ``color_by``, ``colormap``, ``jpeg_subsampling``, ``surface`` and ``surface_kernel`` take a :class:`Smoothing`,
        :class:`Kernel`, :class:`ColorBy`, :class:`Colormap`, :class:`JpegSubsampling`, :class:`SurfaceMode`,
        :class:`SurfaceKernel` or its name
        ("narrow", "anisotropic", "speed", "turbo", "yuv420", "mesh", "sph"); ``fluid_color`` and
        ``absorption`` three numbers, ``color_range`` two (min, max). An unknown name raises
        TypeError (and nothing is sent).

        The client keeps the settings it last sent, starting from
        fc_settings_default(), and sends all of them with the changes applied;
        :attr:`settings` shows them. The server checks the values: one out of
        its domain (a radius < 0, ...) is reported by the next :meth:`render`
        as ``Code.INVALID_VALUE``, and stays in the client's settings until it
        is set again.
        """
        settings = FcSettings.from_buffer_copy(self._settings)
        _apply_settings(settings, fields)
        self._call(_capi.fc_client_set_settings, ctypes.byref(settings))
        self._settings = settings

    @property
    def settings(self):
        """The settings last sent (or the defaults), as a dict of fc_settings' fields."""
        return _settings_dict(self._settings)

    # -- scene images --

    def set_background(self, image):
        """Sends a background image drawn behind the fluid and refracted through it.

        ``image``: the bytes of a PNG, JPEG or EXR file
        (fc_client_set_background_bytes), a path to one
        (fc_client_set_background_file), or None for the built-in floor and
        sky. A file that does not decode is reported by the next :meth:`render`
        (``Code.INVALID_VALUE``); an unreadable path raises ``Code.IO`` here.
        """
        if image is None:
            self._call(_capi.fc_client_set_background_bytes, None, 0)
        elif isinstance(image, (str, os.PathLike)):
            self._call(_capi.fc_client_set_background_file, os.fsencode(image))
        else:
            data = bytes(image)
            self._call(_capi.fc_client_set_background_bytes, data, len(data))

    def set_environment(self, faces):
        """Sends an environment cube map reflected in the fluid instead of the procedural sky.

        ``faces``: six images in the order +X, -X, +Y, -Y, +Z, -Z, each the
        bytes of an image file (fc_client_set_environment_bytes) or, all six,
        paths (fc_client_set_environment_files); square and of one size. None
        goes back to the procedural sky.
        """
        if faces is None:
            self._call(_capi.fc_client_set_environment_bytes, None, None)
            return
        faces = list(faces)
        if len(faces) != 6:
            raise ValueError("set_environment: expected 6 faces (+X, -X, +Y, -Y, +Z, -Z), got %d" % len(faces))
        if all(isinstance(f, (str, os.PathLike)) for f in faces):
            paths = (ctypes.c_char_p * 6)(*[os.fsencode(f) for f in faces])
            self._call(_capi.fc_client_set_environment_files, paths)
            return
        blobs = [bytes(f) for f in faces]
        buffers = [ctypes.create_string_buffer(b, len(b)) for b in blobs]
        data = (ctypes.c_void_p * 6)(*[ctypes.addressof(b) for b in buffers])
        sizes = (ctypes.c_size_t * 6)(*[len(b) for b in blobs])
        self._call(_capi.fc_client_set_environment_bytes, data, sizes)

    # -- meshes --

    def upload_mesh(self, vertices, indices=None, normals=None, id=None, color=None, opacity=None, transform=None,
                    hide_near=None):
        """Sends a triangle mesh drawn with the fluid (fc_client_upload_mesh); returns the :class:`Mesh` sent.

        ``vertices`` (V, 3) and ``normals`` (V, 3, or None for flat faces)
        float32, ``indices`` (T, 3) uint32, counter-clockwise seen from
        outside: numpy arrays already of these types and C-contiguous are
        encoded from where they are, without a copy; others are converted once
        (see :class:`Mesh`). Or a prepared :class:`Mesh` as ``vertices``,
        alone. The rest, when given: ``id`` (default 0: a mesh of an id already
        sent replaces it), ``color`` (linear RGB in [0, 1], default 0.8 grey),
        ``opacity`` (default 1: opaque, hides the fluid behind it and is
        refracted by it; below 1: glass blended over the fluid), ``transform``
        (3x4 or 4x4 matrix or 12 numbers; default identity) and ``hide_near``
        (True: faces turned toward the camera are not drawn, for a tank's near
        walls). A producer's meshes (after :meth:`publish`) show in every
        viewer's images of its session.

        Raises :class:`Error` without sending: ``Code.INVALID_VALUE`` for an
        index >= V or < 0 (naming the triangle), a vertex or normal that is not
        finite, a colour or opacity outside [0, 1]; ``Code.LIMIT`` beyond 2^24
        vertices or triangles; ``Code.TOO_LARGE`` beyond the server's message
        limit. The server's rejections (``Code.LIMIT`` for a 65th mesh or one
        beyond the connection's memory) come from the next :meth:`render`.
        """
        mesh = as_mesh(vertices, indices, normals=normals, id=id, color=color, opacity=opacity,
                       transform=transform, hide_near=hide_near)
        self._call(_capi.fc_client_upload_mesh, ctypes.byref(mesh.c_mesh))
        return mesh

    def remove_mesh(self, id):
        """Removes mesh ``id`` (fc_client_remove_mesh); no error when there is none."""
        self._call(_capi.fc_client_remove_mesh, _uint32("mesh id", id))

    def move_meshes(self, transforms):
        """Places meshes already sent anew, all in one message (fc_client_move_meshes).

        ``transforms``: {id: transform} or (id, transform) pairs, at most 64
        distinct ids; each transform as for :meth:`upload_mesh` (a 3x4 or 4x4
        matrix or 12 numbers; world = R v + t). For a simulation's rigid
        bodies, once per frame. The server moves all of them or, when one id
        was never sent, none: ``Code.BAD_STATE`` from the next :meth:`render`.
        Raises, unsent: ``Code.LIMIT`` for more than 64 entries,
        ``Code.INVALID_VALUE`` for an id given twice or a transform that is not finite.
        """
        entries, count = transform_entries(transforms)
        self._call(_capi.fc_client_move_meshes, entries, count)

    def move_mesh(self, id, transform):
        """Places mesh ``id`` anew: :meth:`move_meshes` with one entry."""
        self.move_meshes([(id, transform)])

    # -- rendering --

    def render_result(self, format="png", quality=0, aov="color"):
        """Renders the current frame, camera and settings and returns the :class:`Image` (fc_client_render).

        ``format``: "png", "jpeg", "exr" or "raw" (or a :class:`Format`);
        ``quality``: JPEG quality 1..100, 0 for the server's default (90);
        ``aov``: "color", "depth", "smoothed_depth", "thickness", "normal" or
        "noise" (or an :class:`Aov`); PNG and JPEG hold colour only.

        Raises :class:`Error`, with the server's code and message, when the
        server rejected this request or an earlier frame, camera, settings or
        scene image of this client (``Code.INVALID_VALUE`` for a NaN position or
        a negative radius, ``Code.BAD_STATE`` before any frame, ...).
        """
        request = _request(format, quality, aov)
        result = FcImageResult()
        try:
            self._call(_capi.fc_client_render, ctypes.byref(request), ctypes.byref(result))
            return Image(result)
        finally:
            _capi.fc_image_result_free(ctypes.byref(result))

    def render(self, format="png", quality=0, aov="color"):
        """Renders and returns the encoded image's bytes: a complete PNG, JPEG or EXR file, or RAW rows.

        Arguments and errors as for :meth:`render_result`.
        """
        return self.render_result(format, quality, aov).data

    def render_image(self, aov="color"):
        """Renders as RAW and returns the pixels as a numpy array, top row first.

        ``aov="color"`` gives (H, W, 4) uint8 RGBA; "depth",
        "smoothed_depth", "thickness" and "noise" give (H, W) float32;
        "normal" gives (H, W, 3) float32. The pixels are copied once, from
        libfluidcast's buffer into the array. Errors as for :meth:`render_result`.
        """
        request = _request(Format.RAW, 0, aov)
        result = FcImageResult()
        try:
            self._call(_capi.fc_client_render, ctypes.byref(request), ctypes.byref(result))
            if result.format != Format.RAW:
                raise Error(Code.PROTOCOL, "asked for a RAW image, got format %d" % result.format)
            return _raw_to_array(ctypes.cast(result.data, ctypes.c_void_p).value, result.size, result.width,
                                 result.height, _enum_or_int(Aov, result.aov))
        finally:
            _capi.fc_image_result_free(ctypes.byref(result))

    def mesh(self, attributes="all"):
        """The surface of the current frame extracted by the server as a :class:`SurfaceMesh` of numpy arrays
        (fc_client_extract_surface, PROTOCOL.md section 13).

        The settings' ``surface_cell``, ``surface_kernel`` and
        ``surface_smoothing`` shape it. ``attributes``: "all" (default), None,
        or names among "speed", "density", "velocity", "id"; the mesh has
        those the frame can give (speed and velocity need velocities, density
        densities, id ids). Errors as for :meth:`render_result`
        (``Code.BAD_STATE`` before any frame, ``Code.LIMIT`` for a grid beyond
        the server's budget).
        """
        bits = attribute_bits(attributes)
        mesh = FcSurfaceMesh()
        extract_ms = ctypes.c_float(-1.0)
        try:
            self._call(_capi.fc_client_extract_surface, bits, ctypes.byref(mesh), ctypes.byref(extract_ms))
            return surface_from_c(mesh, extract_ms.value)
        finally:
            _capi.fc_surface_mesh_free(ctypes.byref(mesh))

    # -- sessions --

    def publish(self, name):
        """Makes this connection a producer of session ``name`` (fc_client_publish).

        The session is created when it does not exist; several connections
        may publish to one (the ranks of one simulation). From then on
        :meth:`send_frame` / :meth:`upload_frame` publish whole frames
        (numbered 1, 2, ...) and :meth:`send_chunk` parts of frames;
        :meth:`render` renders the session's newest complete frame. Returns the
        session's :class:`SessionStatus`. Raises ``Code.BAD_STATE`` when the
        connection is in a session already, ``Code.INVALID_VALUE`` /
        ``Code.USAGE`` for a name not of 1..64 bytes, ``Code.LIMIT`` when the
        server holds its maximum of sessions.
        """
        status = FcSessionStatus()
        self._call(_capi.fc_client_publish, name.encode(), ctypes.byref(status))
        return _status(status)

    def subscribe(self, name, format="png", quality=0, aov="color", size=(0, 0)):
        """Makes this connection a viewer of session ``name`` (fc_client_subscribe).

        Every frame published from now on is rendered for this viewer with its
        camera (:meth:`set_camera`; until one is sent, each frame is framed
        automatically at ``size``, (0, 0) for the server's default 1280x720)
        and settings, in ``format``/``quality``/``aov`` as for :meth:`render`;
        read the images with :meth:`next_image`. Returns the session's
        :class:`SessionStatus`. Errors as for :meth:`publish`, plus those of a
        render request for the format and ``Code.LIMIT`` for a size beyond the
        server's.
        """
        request = _request(format, quality, aov)
        width, height = _size("size", size)
        status = FcSessionStatus()
        self._call(_capi.fc_client_subscribe, name.encode(), ctypes.byref(request), width, height,
                   ctypes.byref(status))
        return _status(status)

    def next_image(self):
        """Waits for the next image of the subscribed session, or its end (fc_client_next_image).

        Returns a :class:`StreamImage`; its ``ended`` is True (and it holds no
        image) once the session's producers have all left. The viewer then
        stays on the session's last frame until it leaves: :meth:`set_camera`
        and settings changes still re-render it (``view_change`` images). A RAW stream image
        converts with ``to_array()``. The connect's ``reply_timeout`` bounds the
        wait (``Code.IO`` when it passes). Raises ``Code.USAGE`` when not
        subscribed, the server's code when it rejected an earlier request of
        this client or could not render for this viewer (the subscription
        stays), or a connection error.
        """
        image = FcStreamImage()
        try:
            self._call(_capi.fc_client_next_image, ctypes.byref(image))
            return StreamImage(image)
        finally:
            _capi.fc_stream_image_free(ctypes.byref(image))

    def request_keyframe(self):
        """Asks for an H.264 key frame (fc_client_request_keyframe): the current frame comes again as an IDR.

        For a decoder that lost its place in an H.264 stream; the image comes
        after the one in flight, with ``view_change`` and ``keyframe`` set.
        Raises ``Code.USAGE`` when not subscribed, or a connection error.
        """
        self._call(_capi.fc_client_request_keyframe)

    def leave_session(self):
        """Leaves the session (fc_client_leave_session) and waits for the server's confirmation.

        A producer stops publishing (the session ends for its viewers once its
        last producer has left), a viewer stops receiving images, also one of a
        session that ended (which the server frees once its last viewer has
        left): none arrives after this returns. Raises ``Code.BAD_STATE`` when in no session, or an
        error the server reported for an earlier request (e.g. a chunk).
        """
        self._call(_capi.fc_client_leave_session)

    @property
    def session_ended(self):
        """True when this viewer's session ended (fc_client_session_ended): it still watches the last frame."""
        return bool(_capi.fc_client_session_ended(self._handle))

    def list_sessions(self):
        """The server's live sessions, oldest first, as a list of :class:`SessionStatus` (fc_client_list_sessions)."""
        entries = ctypes.POINTER(FcSessionStatus)()
        count = ctypes.c_uint32()
        self._call(_capi.fc_client_list_sessions, ctypes.byref(entries), ctypes.byref(count))
        try:
            return [_status(entries[i]) for i in range(count.value)]
        finally:
            _capi.fc_session_list_free(entries)

    def upload_frame(self, positions, density=None, velocity=None, ids=None, zstd=False, quantize16=False,
                     zstd_level=0, radius=None):
        """Sends a frame like :meth:`send_frame`, encoded for the wire (fc_client_upload_frame).

        ``zstd=True`` compresses the particle data with zstd (lossless) at
        ``zstd_level`` (0: 3); ``quantize16=True`` sends positions as 16-bit
        offsets in the frame's bounding box (each coordinate off by at most
        extent / 65535 / 2; radii are never quantised). Returns :class:`UploadStats` (plain size, bytes
        sent). Raises ``Code.USAGE`` for an encoding the server did not grant
        (see ``server_info.capabilities``) or, with quantize16, non-finite
        positions; otherwise errors as for :meth:`send_frame`.
        """
        frame = as_frame(positions, density, velocity, ids, radius)
        options = _upload_options(zstd, quantize16, zstd_level)
        stats = FcUploadStats()
        self._call(_capi.fc_client_upload_frame, ctypes.byref(frame.c_frame), ctypes.byref(options),
                   ctypes.byref(stats))
        return UploadStats(stats.raw_bytes, stats.wire_bytes)

    def send_chunk(self, frame_number, index, count, positions, density=None, velocity=None, ids=None, zstd=False,
                   quantize16=False, zstd_level=0, radius=None):
        """Sends chunk ``index`` of ``count`` of frame ``frame_number`` of the published session (fc_client_send_chunk).

        For a simulation split over ``count`` ranks, each publishing to the
        same session over its own connection: the server renders a frame once
        all its chunks are in, concatenated in index order. Every chunk of a
        frame carries the same ``count`` and attributes. Encoding flags as for
        :meth:`upload_frame`; returns :class:`UploadStats`. The server answers
        only a rejection, reported by the next waiting call or
        :meth:`poll_errors`: ``Code.INVALID_VALUE`` (count 0 or > 4096, index
        >= count), ``Code.DUPLICATE``, ``Code.INCONSISTENT``,
        ``Code.INCOMPLETE`` (chunks missing at the server's timeout),
        ``Code.BAD_STATE`` (not publishing).
        """
        frame = as_frame(positions, density, velocity, ids, radius)
        options = _upload_options(zstd, quantize16, zstd_level)
        stats = FcUploadStats()
        frame_number = int(frame_number)
        if not 0 <= frame_number < 1 << 64:
            raise ValueError("frame_number: %d does not fit uint64" % frame_number)
        self._call(_capi.fc_client_send_chunk, frame_number, _uint32("index", index), _uint32("count", count),
                   ctypes.byref(frame.c_frame), ctypes.byref(options), ctypes.byref(stats))
        return UploadStats(stats.raw_bytes, stats.wire_bytes)

    def poll_errors(self):
        """Reads what the server sent without waiting and raises its first ERROR (fc_client_poll_errors).

        Returns None when there is none; the connection stays usable after a
        server error. For producers that only send and want to hear about
        rejected chunks.
        """
        self._call(_capi.fc_client_poll_errors)


def _status(status):
    return SessionStatus(status.name.decode("utf-8", "replace"), status.producers, status.viewers, status.frames,
                         status.last_frame)


def _upload_options(zstd, quantize16, zstd_level):
    encoding = (UPLOAD_ZSTD if zstd else 0) | (UPLOAD_QUANTIZE16 if quantize16 else 0)
    return FcUploadOptions(encoding, int(zstd_level))
