"""The enumerations and constants of fluidcast_types.h and fluidcast.h.

Each IntEnum member has the value of the C enumerator whose name is the C
prefix plus the member name (``Code.INVALID_VALUE`` is ``FC_ERR_INVALID_VALUE``,
``Format.RAW`` is ``FC_FORMAT_RAW``); :func:`c_name` spells it. The test suite
compiles the C headers and checks every value, and that no enumerator is missing.
"""

import enum


class Code(enum.IntEnum):
    """fc_code: why a call failed. 1..99 are the server's codes, >= 100 local ones."""
    OK = 0
    # wire codes: the server rejected a request
    BAD_MAGIC = 1            #: message header does not start with "FCST"
    VERSION = 2              #: no protocol version in common
    UNKNOWN_TYPE = 3         #: message type not defined by the negotiated version
    TOO_LARGE = 4            #: payload beyond the server's message limit
    MALFORMED = 5            #: payload lengths/counts inconsistent with the message layout
    BAD_STATE = 6            #: message not allowed now (e.g. render before any frame)
    INVALID_VALUE = 7        #: a value out of its domain: NaN position, radius < 0, unknown setting
    LIMIT = 8                #: a configured limit exceeded: particles per frame, image size
    RENDER = 9               #: the GPU could not render this request
    ENCODE = 10              #: the image could not be encoded in the requested format
    INTERNAL = 11            #: server-side failure not caused by the request
    UNAUTHORIZED = 12        #: token missing or wrong
    DUPLICATE = 13           #: a chunk of this frame with this index already arrived
    INCONSISTENT = 14        #: a chunk disagrees with its frame's other chunks
    INCOMPLETE = 15          #: a multi-rank frame still lacked chunks when its timeout passed
    TLS_REQUIRED = 16        #: the port speaks TLS and this client did not (connect with tls:// or tls=True)
    # local codes
    IO = 100                 #: file or socket I/O failed, or a wait for the server timed out
    CONNECT = 101            #: could not reach the server
    CLOSED = 102             #: the connection was lost, the server said goodbye, or the client is closed
    PROTOCOL = 103           #: the server sent bytes that break the protocol
    PARSE = 104              #: a particle file is malformed
    GL = 105                 #: EGL/GL setup or execution failed
    NOMEM = 106              #: an allocation failed
    USAGE = 107              #: an invalid argument (malformed address, capability not granted, ...)
    TLS_UNKNOWN_CA = 108     #: the server's certificate does not chain to a trusted CA (tls_ca)
    TLS_NAME_MISMATCH = 109  #: the server's certificate does not name the host connected to
    TLS_EXPIRED = 110        #: the server's certificate has expired or is not valid yet
    TLS_PLAINTEXT_PEER = 111 #: TLS asked for, but the server answered in clear
    TLS_CLIENT_CERT = 112    #: the server wants a client certificate it trusts (tls_cert, tls_key)
    TLS = 113                #: another TLS failure: certificate files that do not load, a failed handshake


class Format(enum.IntEnum):
    """fc_image_format: how an image is encoded."""
    PNG = 1
    JPEG = 2
    EXR = 3
    RAW = 4  #: uncompressed rows, top to bottom: RGBA8 for colour, little-endian float32 for AOVs
    H264 = 5  #: colour only: one H.264 access unit (Annex B); a RENDER's is an IDR frame of its own


class Aov(enum.IntEnum):
    """fc_aov: what an image shows."""
    COLOR = 0           #: shaded fluid over the background, RGBA
    DEPTH = 1           #: linear view-space depth before smoothing, 1 float, 0 = no fluid
    SMOOTHED_DEPTH = 2  #: linear view-space depth after smoothing, 1 float, 0 = no fluid
    THICKNESS = 3       #: accumulated fluid thickness, 1 float
    NORMAL = 4          #: view-space normal of the smoothed surface, 3 floats (0 where no fluid)
    NOISE = 5           #: per-pixel noise/foam magnitude, 1 float


class Smoothing(enum.IntEnum):
    """fc_smoothing: how the depth of the splatted spheres is smoothed."""
    NONE = 0
    CURVATURE = 1   #: screen-space curvature flow (van der Laan et al. 2009)
    BILATERAL = 2   #: separable bilateral Gaussian
    BINOMIAL = 3    #: binomial filter with silhouette map
    NARROW = 4      #: narrow-range filter (Truong & Yuksel 2018), the default


class Kernel(enum.IntEnum):
    """fc_kernel: the shape each particle is splatted as."""
    SPHERE = 0       #: a sphere of the settings' radius
    ANISOTROPIC = 1  #: an ellipsoid stretched along its neighbours (Yu & Turk 2013)


class ColorBy(enum.IntEnum):
    """fc_color_by: the particle attribute the fluid is tinted by (fc_settings.color_by)."""
    NONE = 0     #: the settings' fluid_color
    SPEED = 1    #: |velocity|: the frame must carry velocities
    DENSITY = 2  #: density: the frame must carry densities


class Colormap(enum.IntEnum):
    """fc_colormap: the colours an attribute's color_range runs through."""
    VIRIDIS = 0
    PLASMA = 1
    INFERNO = 2
    MAGMA = 3
    CIVIDIS = 4
    COOLWARM = 5
    TURBO = 6


class JpegSubsampling(enum.IntEnum):
    """fc_jpeg_subsampling: JPEG chroma, 4:4:4 (every pixel's colour) or 4:2:0 (one per 2x2 pixels)."""
    YUV444 = 0
    YUV420 = 1


class SurfaceMode(enum.IntEnum):
    """fc_surface_mode: how the fluid's surface is made (fc_settings.surface)."""
    SCREEN = 0  #: splatted and smoothed in screen space
    MESH = 1    #: an isosurface mesh extracted from the particles' field


class SurfaceKernel(enum.IntEnum):
    """fc_surface_kernel: the field a surface mesh is an isosurface of (fc_settings.surface_kernel)."""
    METABALL = 0     #: Wyvill's metaballs, radius of influence 2 radii
    SPH = 1          #: the cubic-spline SPH kernel, support 2 radii
    ANISOTROPIC = 2  #: metaballs on the anisotropic ellipsoids


class SettingType(enum.IntEnum):
    """fc_setting_type: how a setting of the table (fc_settings.h) is stored and what it may be."""
    FLOAT = 1    #: ``count`` floats in [min, max]
    UINT = 2     #: one unsigned integer in [min, max]
    CHOICE = 3   #: an index into the setting's choices
    SCALE = 4    #: a pass's resolution: 1, 0.5 or 0.25


class SettingGroup(enum.IntEnum):
    """fc_setting_group: the part of the command line's help a setting is listed under."""
    SURFACE = 0
    SHADING = 1
    COLORING = 2
    IMAGE = 3
    COUNT = 4


class RadiusSource(enum.IntEnum):
    """fc_radius_source: where a render's sphere radius comes from (fc_radius_source_of)."""
    FROM_SETTINGS = 0   #: the settings' radius, > 0, overriding any per-particle radii
    PER_PARTICLE = 1    #: radius 0 and a frame with radii: each particle's own
    ESTIMATED = 2       #: radius 0 and a frame without: estimated from the particle spacing


class Stage(enum.IntEnum):
    """fc_stage: the server-side stages whose durations come with every image."""
    UPLOAD = 0
    DEPTH = 1
    THICKNESS = 2
    SMOOTHING = 3
    COMPOSITE = 4
    READBACK = 5
    ENCODE = 6
    TOTAL = 7       #: request received -> reply queued
    RECEIVE = 8     #: the frame's bytes on the network
    DECODE = 9      #: decompression, dequantisation, chunk assembly
    QUEUE = 10      #: waiting for the GL thread and for an encoder


#: FC_STAGE_COUNT: the number of stage timings in an image result.
STAGE_COUNT = 11
#: FC_ERROR_MESSAGE_MAX: bytes in an fc_error's message, NUL included.
#: Where fluidcastd listens and clients connect unless told otherwise (FC_DEFAULT_PORT, FC_DEFAULT_HOST,
#: FC_DEFAULT_SERVER of fluidcast_types.h).
DEFAULT_PORT = 7450
DEFAULT_HOST = "127.0.0.1"
DEFAULT_SERVER = "%s:%d" % (DEFAULT_HOST, DEFAULT_PORT)
ERROR_MESSAGE_MAX = 256

#: fc_server_info.capabilities bits (FC_SERVER_CAN_*).
SERVER_CAN_STREAM = 0x1
SERVER_CAN_ZSTD = 0x2
SERVER_CAN_QUANTIZE16 = 0x4
SERVER_CAN_DEVICE = 0x8

#: fc_upload_options.encoding bits (FC_UPLOAD_*).
UPLOAD_ZSTD = 0x1
UPLOAD_QUANTIZE16 = 0x2

#: fc_mesh.flags bits (FC_MESH_*).
MESH_HIDE_NEAR = 0x2

_PREFIX = {
    RadiusSource: "FC_RADIUS_",
    SettingType: "FC_SETTING_",
    SettingGroup: "FC_GROUP_",
    Code: "FC_ERR_",
    Format: "FC_FORMAT_",
    Aov: "FC_AOV_",
    Smoothing: "FC_SMOOTHING_",
    Kernel: "FC_KERNEL_",
    ColorBy: "FC_COLOR_BY_",
    Colormap: "FC_COLORMAP_",
    JpegSubsampling: "FC_JPEG_SUBSAMPLING_",
    SurfaceMode: "FC_SURFACE_MODE_",
    SurfaceKernel: "FC_SURFACE_KERNEL_",
    Stage: "FC_STAGE_",
}

#: The C enum type each IntEnum mirrors.
C_TYPES = {
    RadiusSource: "fc_radius_source",
    SettingType: "fc_setting_type",
    SettingGroup: "fc_setting_group",
    Code: "fc_code",
    Format: "fc_image_format",
    Aov: "fc_aov",
    Smoothing: "fc_smoothing",
    Kernel: "fc_kernel",
    ColorBy: "fc_color_by",
    Colormap: "fc_colormap",
    JpegSubsampling: "fc_jpeg_subsampling",
    SurfaceMode: "fc_surface_mode",
    SurfaceKernel: "fc_surface_kernel",
    Stage: "fc_stage",
}

#: The per-vertex attributes of an extracted surface (fc_surface_mesh.h), as bits.
SURFACE_SPEED = 1
SURFACE_DENSITY = 2
SURFACE_VELOCITY = 4
SURFACE_ID = 8

#: The #define'd and counted constants above, by their C names.
C_CONSTANTS = {
    "FC_SURFACE_SPEED": SURFACE_SPEED,
    "FC_SURFACE_DENSITY": SURFACE_DENSITY,
    "FC_SURFACE_VELOCITY": SURFACE_VELOCITY,
    "FC_SURFACE_ID": SURFACE_ID,
    "FC_STAGE_COUNT": STAGE_COUNT,
    "FC_ERROR_MESSAGE_MAX": ERROR_MESSAGE_MAX,
    "FC_SERVER_CAN_STREAM": SERVER_CAN_STREAM,
    "FC_SERVER_CAN_ZSTD": SERVER_CAN_ZSTD,
    "FC_SERVER_CAN_QUANTIZE16": SERVER_CAN_QUANTIZE16,
    "FC_SERVER_CAN_DEVICE": SERVER_CAN_DEVICE,
    "FC_UPLOAD_ZSTD": UPLOAD_ZSTD,
    "FC_UPLOAD_QUANTIZE16": UPLOAD_QUANTIZE16,
    "FC_MESH_HIDE_NEAR": MESH_HIDE_NEAR,
    "FC_DEFAULT_PORT": DEFAULT_PORT,
    "FC_DEFAULT_HOST": DEFAULT_HOST,
    "FC_DEFAULT_SERVER": DEFAULT_SERVER,
}


def c_name(member):
    """The C enumerator an IntEnum member mirrors, e.g. ``FC_ERR_INVALID_VALUE``."""
    if member is Code.OK:
        return "FC_OK"
    return _PREFIX[type(member)] + member.name


def parse(enum_type, value, what):
    """An enum member from a member, an int, or a case-insensitive name ("png", "narrow").

    Raises ValueError for an unknown name or number and TypeError for other types.
    """
    if isinstance(value, enum_type):
        return value
    if isinstance(value, str):
        try:
            return enum_type[value.strip().upper().replace("-", "_")]
        except KeyError:
            names = ", ".join(m.name.lower() for m in enum_type)
            raise ValueError("%s: unknown %s %r (one of %s)" % (what, enum_type.__name__, value, names)) from None
    if isinstance(value, int) and not isinstance(value, bool):
        try:
            return enum_type(value)
        except ValueError:
            raise ValueError("%s: %d is no %s" % (what, value, enum_type.__name__)) from None
    raise TypeError("%s: expected a %s, its name or number, got %r" % (what, enum_type.__name__, value))
