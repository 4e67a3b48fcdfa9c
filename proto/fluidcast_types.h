/* fluidcast_types.h — the data both ends of the wire share: particle frames,
 * cameras, render settings, image requests and typed errors.
 *
 * This header is public (installed next to fluidcast.h) and depends on nothing
 * but the C standard library. Everything here is plain data; the functions that
 * operate on it live in fc_frame.h / fc_error.h (proto library). */
#ifndef FLUIDCAST_TYPES_H
#define FLUIDCAST_TYPES_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Errors -------------------------------------------------------------
 * Codes 1..99 travel on the wire (ERROR message, see proto/PROTOCOL.md);
 * codes >= 100 are local to one process and never sent. */
typedef enum fc_code {
    FC_OK = 0,
    /* wire codes */
    FC_ERR_BAD_MAGIC = 1,        /* message header does not start with "FCST"; connection closed */
    FC_ERR_VERSION = 2,          /* no protocol version in common */
    FC_ERR_UNKNOWN_TYPE = 3,     /* message type not defined by the negotiated version */
    FC_ERR_TOO_LARGE = 4,        /* payload length beyond the server's message limit; connection closed */
    FC_ERR_MALFORMED = 5,        /* payload lengths/counts inconsistent with the message layout */
    FC_ERR_BAD_STATE = 6,        /* message not allowed now (e.g. FRAME before HELLO, RENDER before FRAME) */
    FC_ERR_INVALID_VALUE = 7,    /* a value out of its domain: NaN/Inf position, radius <= 0, unknown setting */
    FC_ERR_LIMIT = 8,            /* a configured limit exceeded: particles per frame, image size */
    FC_ERR_RENDER = 9,           /* the GPU could not render this request */
    FC_ERR_ENCODE = 10,          /* the image could not be encoded in the requested format */
    FC_ERR_INTERNAL = 11,        /* server-side failure not caused by the request (out of memory, ...) */
    FC_ERR_UNAUTHORIZED = 12,    /* authentication required or failed (PROTOCOL.md 4.3); connection closed */
    FC_ERR_DUPLICATE = 13,       /* a chunk of this frame with this index already arrived */
    FC_ERR_INCONSISTENT = 14,    /* a chunk disagrees with its frame's other chunks (count K, attributes) */
    FC_ERR_INCOMPLETE = 15,      /* a multi-rank frame still lacked chunks when its timeout passed */
    FC_ERR_TLS_REQUIRED = 16,    /* a client without TLS reached a TLS port (PROTOCOL.md 1.2); connection closed */
    /* local codes */
    FC_ERR_IO = 100,             /* file or socket I/O failed (see message) */
    FC_ERR_CONNECT = 101,        /* could not reach the server */
    FC_ERR_CLOSED = 102,         /* the peer closed the connection */
    FC_ERR_PROTOCOL = 103,       /* the peer sent bytes that break the protocol */
    FC_ERR_PARSE = 104,          /* a particle file is malformed */
    FC_ERR_GL = 105,             /* EGL/GL setup or execution failed */
    FC_ERR_NOMEM = 106,          /* allocation failed */
    FC_ERR_USAGE = 107,          /* a caller passed an invalid argument */
    /* why a TLS connection failed (PROTOCOL.md 1.2) */
    FC_ERR_TLS_UNKNOWN_CA = 108,     /* the server's certificate does not chain to a trusted CA */
    FC_ERR_TLS_NAME_MISMATCH = 109,  /* the server's certificate does not name the host connected to */
    FC_ERR_TLS_EXPIRED = 110,        /* the server's certificate has expired or is not valid yet */
    FC_ERR_TLS_PLAINTEXT_PEER = 111, /* TLS asked for, but the server answered in clear (a plaintext port) */
    FC_ERR_TLS_CLIENT_CERT = 112,    /* the server wants a client certificate, or refused the one sent */
    FC_ERR_TLS = 113                 /* any other TLS failure: unreadable certificate files, a failed handshake */
} fc_code;

#define FC_ERROR_MESSAGE_MAX 256

/* ---- Addresses ------------------------------------------------------------
 * Where fluidcastd listens and clients connect unless told otherwise. The
 * grammar of an address is fc_host_port.h's (proto/PROTOCOL.md section 1.1). */
#define FC_DEFAULT_PORT 7450
#define FC_DEFAULT_HOST "127.0.0.1"
#define FC_STRINGIFY_(x) #x
#define FC_STRINGIFY(x) FC_STRINGIFY_(x)
#define FC_DEFAULT_SERVER FC_DEFAULT_HOST ":" FC_STRINGIFY(FC_DEFAULT_PORT)   /* "127.0.0.1:7450" */

/* An error value: a code plus a human-readable reason. Functions that can fail
 * return an fc_code and, when given a non-NULL fc_error*, fill it in. */
typedef struct fc_error {
    fc_code code;
    char message[FC_ERROR_MESSAGE_MAX];
} fc_error;

/* ---- Particle frame ------------------------------------------------------
 * The in-memory frame: what a file reader produces, what FRAME carries on the
 * wire and what the renderer consumes. Arrays are owned by the frame
 * (free with fc_frame_free) and NULL when absent. */
typedef struct fc_frame {
    uint64_t count;        /* number of particles */
    float *positions;      /* 3*count floats, x y z interleaved, world units */
    float *density;        /* count floats, or NULL */
    float *velocity;       /* 3*count floats, or NULL */
    uint32_t *ids;         /* count persistent particle ids, or NULL */
    float *radius;         /* count per-particle splat radii in world units, each finite, > 0 and <= 1e6
                              (FC_FRAME_MAX_RADIUS), or NULL: every particle then takes the settings' radius.
                              A settings radius > 0 overrides these (PROTOCOL.md 5) */
} fc_frame;

/* ---- Camera --------------------------------------------------------------
 * Right-handed, OpenGL-style look-at with a vertical field of view. The image
 * size is part of the camera because the projection depends on the aspect. */
typedef struct fc_camera {
    float eye[3];
    float target[3];
    float up[3];
    float fov_y_deg;       /* vertical field of view, degrees, in (0, 180) */
    uint32_t width;        /* image width in pixels, >= 1 */
    uint32_t height;       /* image height in pixels, >= 1 */
} fc_camera;

/* ---- Render settings -----------------------------------------------------*/
typedef enum fc_smoothing {
    FC_SMOOTHING_NONE = 0,
    FC_SMOOTHING_CURVATURE = 1,  /* screen-space curvature flow, van der Laan et al. 2009 */
    FC_SMOOTHING_BILATERAL = 2,  /* separable bilateral Gaussian (Janisz 2012, section 4.1.2.1) */
    FC_SMOOTHING_BINOMIAL = 3,   /* binomial filter with silhouette map (Cords & Staadt, Instant Liquids) */
    FC_SMOOTHING_NARROW = 4      /* narrow-range filter (Truong & Yuksel 2018) */
} fc_smoothing;

/* The shape each particle is splatted as. */
typedef enum fc_kernel {
    FC_KERNEL_SPHERE = 0,        /* a sphere of the settings' radius */
    FC_KERNEL_ANISOTROPIC = 1    /* an ellipsoid stretched along its neighbours (Yu & Turk 2013): flat on
                                    sheets and surfaces, long on jets, a sphere where it has few neighbours */
} fc_kernel;

/* How the fluid's surface is made (fc_settings.surface). */
typedef enum fc_surface_mode {
    FC_SURFACE_MODE_SCREEN = 0,  /* splatted and smoothed in screen space (van der Laan et al. 2009) */
    FC_SURFACE_MODE_MESH = 1     /* an isosurface extracted from the particles' field and rasterised (Janisz
                                    section 4.2; docs/rendering.md, surface meshes) */
} fc_surface_mode;

/* The field whose isosurface a surface mesh is (fc_settings.surface_kernel). */
typedef enum fc_surface_kernel {
    FC_SURFACE_KERNEL_METABALL = 0,     /* Wyvill's soft-object metaballs of radius of influence 2 radii (Janisz) */
    FC_SURFACE_KERNEL_SPH = 1,          /* the cubic-spline SPH kernel of support 2 radii */
    FC_SURFACE_KERNEL_ANISOTROPIC = 2   /* metaballs on the renderer's anisotropic ellipsoids (Yu & Turk 2013) */
} fc_surface_kernel;

/* What the fluid is coloured by (fc_settings.color_by): a per-particle
 * attribute of the frame, mapped through a colormap. */
typedef enum fc_color_by {
    FC_COLOR_BY_NONE = 0,        /* the fluid colour of the settings */
    FC_COLOR_BY_SPEED = 1,       /* |velocity|: the frame must carry velocities */
    FC_COLOR_BY_DENSITY = 2      /* density: the frame must carry densities */
} fc_color_by;

/* Colormaps for fc_settings.colormap: matplotlib's perceptually uniform maps,
 * Moreland's diverging coolwarm and Google's turbo (fc_colormap.h). */
typedef enum fc_colormap {
    FC_COLORMAP_VIRIDIS = 0,
    FC_COLORMAP_PLASMA = 1,
    FC_COLORMAP_INFERNO = 2,
    FC_COLORMAP_MAGMA = 3,
    FC_COLORMAP_CIVIDIS = 4,
    FC_COLORMAP_COOLWARM = 5,
    FC_COLORMAP_TURBO = 6
} fc_colormap;

/* Chroma subsampling of JPEG images (fc_settings.jpeg_subsampling). 4:4:4
 * keeps every pixel's colour (thin coloured features, colormaps, legends);
 * 4:2:0 shares one colour among 2x2 pixels: about 20% smaller files and a
 * faster encode, for streams. */
typedef enum fc_jpeg_subsampling {
    FC_JPEG_SUBSAMPLING_YUV444 = 0,
    FC_JPEG_SUBSAMPLING_YUV420 = 1
} fc_jpeg_subsampling;

/* Every parameter a user may tune. fc_settings_default() gives convincing water;
 * zero is "off" for the optional effects. */
typedef struct fc_settings {
    float radius;              /* sphere radius in world units, overriding any per-particle radii; 0 = each
                                  particle's own radius (fc_frame.radius), or without them an estimate
                                  from the particle spacing */
    fc_smoothing smoothing;
    uint32_t iterations;       /* curvature-flow steps, or filter passes for the other methods */
    uint32_t filter_radius;    /* kernel half-width in pixels (bilateral, binomial, narrow); 0 = from the
                                  projected particle size */
    float smooth_scale;        /* resolution of depth smoothing: 1, 0.5 or 0.25 */
    float fluid_color[3];      /* linear RGB of the fluid seen through a thick layer */
    float absorption[3];       /* Beer-Lambert absorption per particle radius of thickness, per channel: the
                                  same scene in millimetres and in metres looks the same */
    float ior;                 /* index of refraction (Fresnel F0 = ((ior-1)/(ior+1))^2) */
    float refraction;          /* gamma: background offset beta = gamma * thickness, both in pixels (the
                                  thickness as the pixels it spans at its depth); about 1 - 1/ior */
    float specular;            /* Phong specular intensity, >= 0 */
    float shininess;           /* Phong exponent, >= 1 */
    float thickness_scale;     /* resolution of the thickness pass: 1, 0.5 or 0.25 */
    uint32_t thickness_blur;   /* Gaussian blur radius of thickness in pixels; 0 = none */
    float noise;               /* amplitude of the per-particle surface noise; 0 = off */
    float foam;                /* foam intensity (grey foam from noise magnitude, white spray); 0 = off */
    float foam_tau;            /* velocity change (world units per frame) that raises a particle's noise */
    float foam_decay;          /* per-frame factor in [0,1) by which a raised amplitude decays */
    float density_threshold;   /* particles with density below this are spray, not surface; 0 = off */
    fc_kernel kernel;          /* particle shape: spheres or anisotropic ellipsoids */
    uint32_t shadow;           /* 1: the fluid casts a soft shadow on the built-in floor, 0: none */
    float exposure;            /* stops of exposure before the filmic tone map (0 = as lit) */
    fc_color_by color_by;      /* tint the fluid by a particle attribute; NONE: fluid_color. A frame without
                                  the attribute cannot be rendered so (INVALID_VALUE naming it) */
    fc_colormap colormap;      /* the colours the attribute's range runs through */
    float color_range[2];      /* attribute values mapped to the colormap's ends: finite, min < max when
                                  color_by is set; values outside take the end colours, so runs compare */
    fc_jpeg_subsampling jpeg_subsampling; /* chroma subsampling of JPEG images; other formats ignore it */
    uint32_t spray_neighbours; /* particles with fewer neighbours than this within 2.2 particle spacings are
                                  spray (Ihmsen et al. 2012), drawn as small clear droplets; 0 = off */
    fc_surface_mode surface;   /* screen-space splats, or an extracted isosurface mesh */
    float surface_cell;        /* the mesh's grid cell edge in particle radii, (0.25, 4] */
    fc_surface_kernel surface_kernel; /* the field the mesh is an isosurface of */
    uint32_t surface_smoothing;/* Taubin smoothing steps of the mesh (each a shrink and an inflate); 0 = off */
    float contact_shadow;      /* how much the water darkens within 2.5 particle radii (along the view ray) of the
                                  built-in floor, so that its foot shows on a floor of its own grey; 0 = off */
    float depth_dimming;       /* how much what shows through thick water dims (63% of it at 12 particle radii
                                  of thickness), so that a body's far faces read; 0 = off */
    float aerated_foam;        /* how opaque the white foam is where the flow traps air (Ihmsen et al. 2012's
                                  trapped-air potential; needs velocities and spray_neighbours > 0); 0 = off */
} fc_settings;

/* ---- Meshes ---------------------------------------------------------------
 * A triangle mesh drawn with the fluid (MESH, PROTOCOL.md section 12): a
 * solver's tank, obstacle or rigid body. The arrays are the caller's; the
 * codec copies them into the message. */
#define FC_MESH_HIDE_NEAR 2u     /* fc_mesh.flags: faces whose normal points toward the camera are not drawn,
                                    so a tank's near walls do not hide the fluid inside */

typedef struct fc_mesh {
    uint32_t id;               /* several meshes per connection, each replaced by the next MESH of its id */
    uint32_t flags;            /* FC_MESH_HIDE_NEAR or 0 */
    uint32_t vertex_count;     /* V */
    uint32_t triangle_count;   /* T; 0 (with V 0) removes mesh `id` */
    const float *vertices;     /* 3V floats, x y z, in the mesh's own frame */
    const uint32_t *indices;   /* 3T vertex indices, counter-clockwise seen from outside (< V) */
    const float *normals;      /* 3V floats, one per vertex; NULL: flat faces from the winding */
    float color[3];            /* linear RGB, each in [0, 1] */
    float opacity;             /* [0, 1]; 1 opaque, below 1 glass drawn over the fluid */
    float transform[12];       /* 3x4 row-major: world = R v + t with rows (r0 r1 r2 t); identity to start */
} fc_mesh;

/* A new rigid (or any affine) placement of mesh `id` (MESH_TRANSFORM). */
typedef struct fc_mesh_transform {
    uint32_t id;
    float transform[12];       /* as fc_mesh.transform */
} fc_mesh_transform;

/* ---- Image request and reply -------------------------------------------*/
typedef enum fc_image_format {
    FC_FORMAT_PNG = 1,
    FC_FORMAT_JPEG = 2,
    FC_FORMAT_EXR = 3,
    FC_FORMAT_RAW = 4,         /* uncompressed rows, top to bottom: RGBA8 for colour, float32 for AOVs */
    FC_FORMAT_H264 = 5         /* colour only: one H.264 access unit, Annex B byte stream (PROTOCOL.md 10.7);
                                  a RENDER's is a self-contained IDR frame */
} fc_image_format;

/* What the image shows: the shaded colour or one arbitrary output variable. */
typedef enum fc_aov {
    FC_AOV_COLOR = 0,          /* shaded fluid over the background, RGBA */
    FC_AOV_DEPTH = 1,          /* linear view-space depth before smoothing, 1 channel float, 0 = no fluid */
    FC_AOV_SMOOTHED_DEPTH = 2, /* linear view-space depth after smoothing, 1 channel float, 0 = no fluid */
    FC_AOV_THICKNESS = 3,      /* accumulated fluid thickness, 1 channel float */
    FC_AOV_NORMAL = 4,         /* view-space normal of the smoothed surface, RGB float (0 where no fluid) */
    FC_AOV_NOISE = 5           /* per-pixel noise/foam magnitude, 1 channel float */
} fc_aov;

typedef struct fc_render_request {
    fc_image_format format;
    uint32_t quality;          /* JPEG quality 1..100; ignored otherwise */
    fc_aov aov;
} fc_render_request;

/* Server-side stages whose duration is reported with every image. */
typedef enum fc_stage {
    FC_STAGE_UPLOAD = 0,       /* particle upload to the GPU */
    FC_STAGE_DEPTH,            /* sphere depth splatting (and the thickness splat at thickness_scale 1) */
    FC_STAGE_THICKNESS,        /* the thickness splat at reduced scale, its blur and resampling */
    FC_STAGE_SMOOTHING,
    FC_STAGE_COMPOSITE,
    FC_STAGE_READBACK,
    FC_STAGE_ENCODE,
    FC_STAGE_TOTAL,            /* request received -> reply queued */
    /* appended after TOTAL so the numbers above keep their wire values */
    FC_STAGE_RECEIVE,          /* the frame's bytes on the network: first byte -> last byte (all chunks) */
    FC_STAGE_DECODE,           /* decoding the frame: decompression, dequantisation, chunk assembly */
    FC_STAGE_QUEUE,            /* waiting for the GL thread plus waiting for an encoder */
    FC_STAGE_COUNT
} fc_stage;

#ifdef __cplusplus
}
#endif
#endif
