"""ctypes mirrors of the structs in fluidcast_types.h and fluidcast.h, and the
prototypes of every libfluidcast function.

Field for field, in the headers' order and with their names. Each struct class
carries its C name in ``_c_name_``; the test suite compiles a C program from
these classes (offsetof and sizeof of every field, sizeof of every struct) and
compares, so a change to a header that is not made here fails the tests.

C enums are ``int``-sized in the platform ABI; they are declared ``c_int`` here.
"""

from ctypes import (POINTER, Structure, byref, c_bool, c_char, c_char_p, c_double, c_float, c_int, c_size_t, c_uint8,
                    c_uint16, c_uint32, c_uint64, c_void_p)

from . import _library
from ._enums import ERROR_MESSAGE_MAX, STAGE_COUNT, SettingType

c_enum = c_int


class FcError(Structure):
    """fc_error: a code and a NUL-terminated reason."""
    _c_name_ = "fc_error"
    _fields_ = [
        ("code", c_enum),
        ("message", c_char * ERROR_MESSAGE_MAX),
    ]


class FcFrame(Structure):
    """fc_frame: particle arrays, NULL when absent (positions always present)."""
    _c_name_ = "fc_frame"
    _fields_ = [
        ("count", c_uint64),
        ("positions", POINTER(c_float)),   # 3*count, x y z interleaved
        ("density", POINTER(c_float)),     # count, or NULL
        ("velocity", POINTER(c_float)),    # 3*count, or NULL
        ("ids", POINTER(c_uint32)),        # count, or NULL
        ("radius", POINTER(c_float)),      # count, per-particle radii, or NULL
    ]


class FcCamera(Structure):
    """fc_camera: look-at camera with a vertical field of view and the image size."""
    _c_name_ = "fc_camera"
    _fields_ = [
        ("eye", c_float * 3),
        ("target", c_float * 3),
        ("up", c_float * 3),
        ("fov_y_deg", c_float),
        ("width", c_uint32),
        ("height", c_uint32),
    ]


class FcSettingSpec(Structure):
    """fc_setting_spec: one entry of the settings' table (fc_settings.h)."""
    _c_name_ = "fc_setting_spec"
    _fields_ = [
        ("name", c_char_p),
        ("key", c_uint16),
        ("type", c_enum),                  # fc_setting_type
        ("count", c_uint32),
        ("offset", c_size_t),
        ("initial", c_float * 3),
        ("min", c_double),
        ("max", c_double),
        ("flags", c_uint32),
        ("choices", POINTER(c_char_p)),
        ("separator", c_char),
        ("group", c_enum),                 # fc_setting_group
        ("option", c_char_p),
        ("metavar", c_char_p),
        ("help", c_char_p),
    ]


class FcMesh(Structure):
    """fc_mesh: a triangle mesh drawn with the fluid (MESH); the arrays are the caller's."""
    _c_name_ = "fc_mesh"
    _fields_ = [
        ("id", c_uint32),
        ("flags", c_uint32),               # FC_MESH_HIDE_NEAR or 0
        ("vertex_count", c_uint32),
        ("triangle_count", c_uint32),
        ("vertices", POINTER(c_float)),    # 3*vertex_count
        ("indices", POINTER(c_uint32)),    # 3*triangle_count, each < vertex_count
        ("normals", POINTER(c_float)),     # 3*vertex_count, or NULL: flat faces
        ("color", c_float * 3),
        ("opacity", c_float),
        ("transform", c_float * 12),       # 3x4 row-major (R | t)
    ]


class FcMeshTransform(Structure):
    """fc_mesh_transform: a new placement of mesh ``id`` (MESH_TRANSFORM)."""
    _c_name_ = "fc_mesh_transform"
    _fields_ = [
        ("id", c_uint32),
        ("transform", c_float * 12),
    ]


class FcRenderRequest(Structure):
    """fc_render_request: image format, JPEG quality, AOV."""
    _c_name_ = "fc_render_request"
    _fields_ = [
        ("format", c_enum),                # fc_image_format
        ("quality", c_uint32),
        ("aov", c_enum),                   # fc_aov
    ]


class FcConnectOptions(Structure):
    """fc_connect_options: client name, timeouts, token, TLS."""
    _c_name_ = "fc_connect_options"
    _fields_ = [
        ("client_name", c_char_p),
        ("connect_timeout_ms", c_uint32),
        ("reply_timeout_ms", c_uint32),
        ("token", c_char_p),
        ("tls", c_int),
        ("tls_ca_file", c_char_p),
        ("tls_cert_file", c_char_p),
        ("tls_key_file", c_char_p),
    ]


class FcServerInfo(Structure):
    """fc_server_info: what the server announced in its WELCOME."""
    _c_name_ = "fc_server_info"
    _fields_ = [
        ("protocol_version", c_uint32),
        ("server_version", c_char * 32),
        ("renderer", c_char * 128),
        ("max_particles", c_uint64),
        ("max_width", c_uint32),
        ("max_height", c_uint32),
        ("max_message", c_uint32),
        ("capabilities", c_uint32),
        ("device", c_char * 128),
    ]


class FcImageResult(Structure):
    """fc_image_result: an encoded image; data owned by the result (fc_image_result_free)."""
    _c_name_ = "fc_image_result"
    _fields_ = [
        ("width", c_uint32),
        ("height", c_uint32),
        ("format", c_enum),                # fc_image_format
        ("aov", c_enum),                   # fc_aov
        ("stage_ms", c_float * STAGE_COUNT),
        ("data", POINTER(c_uint8)),
        ("size", c_size_t),
    ]


class FcSessionStatus(Structure):
    """fc_session_status: a named session's state."""
    _c_name_ = "fc_session_status"
    _fields_ = [
        ("name", c_char * 65),
        ("producers", c_uint32),
        ("viewers", c_uint32),
        ("frames", c_uint64),
        ("last_frame", c_uint64),
    ]


class FcStreamImage(Structure):
    """fc_stream_image: one image of a subscribed session, or its end."""
    _c_name_ = "fc_stream_image"
    _fields_ = [
        ("image", FcImageResult),
        ("frame_number", c_uint64),
        ("sequence", c_uint64),
        ("missed", c_uint32),
        ("refresh", c_int),
        ("view_change", c_int),
        ("ended", c_int),
        ("keyframe", c_int),
    ]


class FcUploadOptions(Structure):
    """fc_upload_options: FC_UPLOAD_* encoding bits and the zstd level."""
    _c_name_ = "fc_upload_options"
    _fields_ = [
        ("encoding", c_uint32),
        ("zstd_level", c_int),
    ]


class FcUploadStats(Structure):
    """fc_upload_stats: bytes a frame takes plain and bytes actually sent."""
    _c_name_ = "fc_upload_stats"
    _fields_ = [
        ("raw_bytes", c_uint64),
        ("wire_bytes", c_uint64),
    ]


class FcSurfaceMesh(Structure):
    """fc_surface_mesh (fc_surface_mesh.h): an extracted surface; arrays owned by it (fc_surface_mesh_free)."""
    _c_name_ = "fc_surface_mesh"
    _fields_ = [
        ("vertex_count", c_uint32),
        ("triangle_count", c_uint32),
        ("positions", POINTER(c_float)),
        ("normals", POINTER(c_float)),
        ("indices", POINTER(c_uint32)),
        ("attributes", c_uint32),          # FC_SURFACE_* bits
        ("speed", POINTER(c_float)),
        ("density", POINTER(c_float)),
        ("velocity", POINTER(c_float)),
        ("id", POINTER(c_uint32)),
    ]


#: Every struct mirrored, for the layout test.
lib, library_path = _library.load()


def settings_table():
    """The library's settings table (fc_settings_table): a list of FcSettingSpec, in key order."""
    # Declared here too: FcSettings, whose fields come from this table, is
    # needed before _declare() can set up every other prototype.
    fn = lib.fc_settings_table
    fn.restype = POINTER(FcSettingSpec)
    fn.argtypes = [POINTER(c_size_t)]
    count = c_size_t()
    table = fn(byref(count))
    return [table[i] for i in range(count.value)]


def _settings_fields():
    """fc_settings' fields from the table, in memory order: every value is 4 bytes
    (a float, a uint32_t or an int-sized enum), so offsets follow from the counts."""
    fields, offset = [], 0
    for spec in sorted(settings_table(), key=lambda s: s.offset):
        if spec.offset != offset:
            raise ImportError("fluidcast: the settings table leaves a gap at byte %d of fc_settings" % offset)
        scalar = {SettingType.FLOAT: c_float, SettingType.SCALE: c_float, SettingType.UINT: c_uint32,
                  SettingType.CHOICE: c_uint32}[SettingType(spec.type)]
        fields.append((spec.name.decode(), scalar * spec.count if spec.count > 1 else scalar))
        offset += 4 * spec.count
    return fields


class FcSettings(Structure):
    """fc_settings: every render parameter, its fields made from the library's settings table
    (fc_settings.h: each field's meaning, domain and default)."""
    _c_name_ = "fc_settings"
    _fields_ = _settings_fields()


STRUCTS = (FcError, FcFrame, FcCamera, FcSettings, FcSettingSpec, FcMesh, FcMeshTransform, FcRenderRequest, FcConnectOptions, FcServerInfo,
           FcImageResult, FcSessionStatus, FcStreamImage, FcUploadOptions, FcUploadStats, FcSurfaceMesh)

c_client_p = c_void_p  # fc_client *, opaque
_E = POINTER(FcError)

_SPEC_P = POINTER(FcSettingSpec)

# name: (restype, argtypes), as declared in fluidcast.h, fc_settings.h and fc_surface_mesh.h
_PROTOTYPES = {
    "fc_settings_table": (_SPEC_P, [POINTER(c_size_t)]),
    "fc_setting_by_key": (_SPEC_P, [c_uint32]),
    "fc_setting_by_name": (_SPEC_P, [c_char_p]),
    "fc_setting_by_option": (_SPEC_P, [c_char_p]),
    "fc_settings_default": (None, [POINTER(FcSettings)]),
    "fc_smoothing_default_iterations": (c_uint32, [c_enum]),
    "fc_settings_validate": (c_enum, [POINTER(FcSettings), _E]),
    "fc_setting_validate": (c_enum, [_SPEC_P, POINTER(FcSettings), _E]),
    "fc_setting_field": (c_void_p, [_SPEC_P, POINTER(FcSettings)]),
    "fc_setting_field_const": (c_void_p, [_SPEC_P, POINTER(FcSettings)]),
    "fc_setting_choice_count": (c_uint32, [_SPEC_P]),
    "fc_radius_source_of": (c_enum, [POINTER(FcSettings), c_bool]),
    "fc_client_connect": (c_enum, [c_char_p, POINTER(FcConnectOptions), POINTER(c_client_p), _E]),
    "fc_client_connect_session": (c_enum, [c_char_p, c_char_p, POINTER(FcConnectOptions), POINTER(c_client_p), _E]),
    "fc_client_address": (c_char_p, [c_client_p]),
    "fc_client_server_info": (None, [c_client_p, POINTER(FcServerInfo)]),
    "fc_client_send_frame": (c_enum, [c_client_p, POINTER(FcFrame), _E]),
    "fc_client_set_camera": (c_enum, [c_client_p, POINTER(FcCamera), _E]),
    "fc_client_set_settings": (c_enum, [c_client_p, POINTER(FcSettings), _E]),
    "fc_client_set_background_bytes": (c_enum, [c_client_p, c_void_p, c_size_t, _E]),
    "fc_client_set_background_file": (c_enum, [c_client_p, c_char_p, _E]),
    "fc_client_set_environment_bytes": (c_enum, [c_client_p, POINTER(c_void_p), POINTER(c_size_t), _E]),
    "fc_client_set_environment_files": (c_enum, [c_client_p, POINTER(c_char_p), _E]),
    "fc_mesh_defaults": (None, [POINTER(FcMesh)]),
    "fc_client_upload_mesh": (c_enum, [c_client_p, POINTER(FcMesh), _E]),
    "fc_client_remove_mesh": (c_enum, [c_client_p, c_uint32, _E]),
    "fc_client_move_meshes": (c_enum, [c_client_p, POINTER(FcMeshTransform), c_uint32, _E]),
    "fc_client_render": (c_enum, [c_client_p, POINTER(FcRenderRequest), POINTER(FcImageResult), _E]),
    "fc_image_result_free": (None, [POINTER(FcImageResult)]),
    "fc_client_extract_surface": (c_enum, [c_client_p, c_uint32, POINTER(FcSurfaceMesh), POINTER(c_float), _E]),
    "fc_surface_mesh_free": (None, [POINTER(FcSurfaceMesh)]),
    "fc_client_close": (None, [c_client_p]),
    "fc_client_publish": (c_enum, [c_client_p, c_char_p, POINTER(FcSessionStatus), _E]),
    "fc_client_subscribe": (c_enum, [c_client_p, c_char_p, POINTER(FcRenderRequest), c_uint32, c_uint32,
                                     POINTER(FcSessionStatus), _E]),
    "fc_client_next_image": (c_enum, [c_client_p, POINTER(FcStreamImage), _E]),
    "fc_stream_image_free": (None, [POINTER(FcStreamImage)]),
    "fc_client_leave_session": (c_enum, [c_client_p, _E]),
    "fc_client_session_ended": (c_int, [c_client_p]),
    "fc_client_request_keyframe": (c_enum, [c_client_p, _E]),
    "fc_client_list_sessions": (c_enum, [c_client_p, POINTER(POINTER(FcSessionStatus)), POINTER(c_uint32), _E]),
    "fc_session_list_free": (None, [POINTER(FcSessionStatus)]),
    "fc_client_upload_frame": (c_enum, [c_client_p, POINTER(FcFrame), POINTER(FcUploadOptions),
                                        POINTER(FcUploadStats), _E]),
    "fc_client_send_chunk": (c_enum, [c_client_p, c_uint64, c_uint32, c_uint32, POINTER(FcFrame),
                                      POINTER(FcUploadOptions), POINTER(FcUploadStats), _E]),
    "fc_client_poll_errors": (c_enum, [c_client_p, _E]),
    "fc_client_wait_input": (c_enum, [c_client_p, c_uint32, POINTER(c_int), _E]),
}


def _declare():
    missing = []
    for name, (restype, argtypes) in _PROTOTYPES.items():
        try:
            fn = getattr(lib, name)
        except AttributeError:
            missing.append(name)
            continue
        fn.restype = restype
        fn.argtypes = argtypes
        globals()[name] = fn
    if missing:
        raise ImportError("fluidcast: %s lacks %s (a libfluidcast older than this binding?)"
                          % (library_path, ", ".join(missing)))


_declare()
