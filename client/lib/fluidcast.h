/* fluidcast.h — libfluidcast, the client library simulation codes link to push
 * particle frames and cameras to a fluidcastd render daemon and get images back.
 *
 * A session looks like:
 *
 *     fc_client *c;
 *     fc_error err;
 *     if (fc_client_connect("render-host:7450", NULL, &c, &err) != FC_OK) { ... }
 *     fc_client_send_frame(c, &frame, &err);
 *     fc_client_set_camera(c, &camera, &err);
 *     fc_image_result img;
 *     fc_render_request req = { FC_FORMAT_PNG, 90, FC_AOV_COLOR };
 *     if (fc_client_render(c, &req, &img, &err) == FC_OK) { write img.data, img.size; }
 *     fc_image_result_free(&img);
 *     fc_client_close(c);
 *
 * Every call blocks until its bytes are sent (and, for connect and render, until
 * the server's reply arrived). A client is not thread-safe: use one client per
 * thread, or serialise the calls. The library keeps no global state.
 *
 * Errors are values: every function that can fail returns an fc_code and, given a
 * non-NULL fc_error*, fills it with the code and a reason. The codes mean:
 *   1..99            the server rejected a request; the code is the server's and
 *                    the message is the server's, prefixed "server: ".
 *   FC_ERR_CONNECT   the server could not be reached (name lookup, refused, timeout).
 *   FC_ERR_CLOSED    the connection was lost or the server said goodbye.
 *   FC_ERR_PROTOCOL  the server sent bytes that break the protocol.
 *   FC_ERR_IO        a socket call failed or a wait for the server timed out.
 *   FC_ERR_NOMEM     an allocation failed.
 *   FC_ERR_USAGE     the caller passed an invalid argument (NULL, malformed address).
 * After FC_ERR_CLOSED, FC_ERR_PROTOCOL or FC_ERR_IO the connection is unusable:
 * later calls return FC_ERR_CLOSED; close the client and connect again. A server
 * error (1..99) leaves the connection usable unless the server closed it. */
#ifndef FLUIDCAST_H
#define FLUIDCAST_H

#include "fc_api.h"
#include "fluidcast_types.h"
#include "fc_settings.h"   /* fc_settings_default, fc_settings_validate and the settings table */
#include "fc_surface_mesh.h" /* fc_surface_mesh, what fc_client_extract_surface returns */

#ifdef __cplusplus
extern "C" {
#endif

/* An open connection to one fluidcastd. Opaque; created by fc_client_connect,
 * released by fc_client_close. */
typedef struct fc_client fc_client;

/* Options for fc_client_connect. A zero-initialised struct (or NULL) means the
 * defaults given per field. */
typedef struct fc_connect_options {
    const char *client_name;      /* shown in the server's log; NULL: "libfluidcast". Truncated to 63 bytes. */
    uint32_t connect_timeout_ms;  /* bound on reaching the server and its WELCOME; 0: 10000 */
    uint32_t reply_timeout_ms;    /* longest silence tolerated while sending or waiting for a
                                     reply (a render can take seconds); 0: wait indefinitely */
    const char *token;            /* the daemon's shared secret (fluidcastd --token-file / FLUIDCAST_TOKEN),
                                     sent in HELLO; NULL or "": none. At most 256 bytes, else FC_ERR_USAGE.
                                     A daemon that wants a token refuses a missing or wrong one with
                                     FC_ERR_UNAUTHORIZED from fc_client_connect. */
    /* TLS (proto/PROTOCOL.md 1.2): the connection is encrypted and the server
     * authenticated before HELLO. Asked for by `tls` or by an address
     * "tls://HOST:PORT" / "tls://srv:NAME"; all zero: in clear, as before. */
    int tls;                      /* nonzero: TLS on TCP addresses ("unix:" with TLS is FC_ERR_USAGE) */
    const char *tls_ca_file;      /* PEM CAs the server's certificate must chain to; NULL: the system's store */
    const char *tls_cert_file;    /* PEM client certificate, for a daemon that wants one (mutual TLS); NULL: none */
    const char *tls_key_file;     /* its private key (PEM); NULL: in tls_cert_file */
} fc_connect_options;

/* What the server announced in its WELCOME. Plain data, copied out of the client. */
typedef struct fc_server_info {
    uint32_t protocol_version;    /* the protocol version in use on this connection */
    char server_version[32];      /* e.g. "fluidcastd 0.1.0", NUL-terminated */
    char renderer[128];           /* the daemon's GL_RENDERER, NUL-terminated */
    uint64_t max_particles;       /* largest frame the server accepts */
    uint32_t max_width;           /* largest image the server renders */
    uint32_t max_height;
    uint32_t max_message;         /* largest message payload, in bytes, the server reads */
    uint32_t capabilities;        /* FC_SERVER_CAN_* bits the server granted this connection */
    char device[128];             /* the daemon's GPU device, e.g. "EGL device 0, /dev/dri/renderD128, CUDA 0"
                                     or "Mesa surfaceless platform (no device)"; "" from a server that did not
                                     grant FC_SERVER_CAN_DEVICE (an older one). NUL-terminated */
} fc_server_info;

/* A rendered image as the server encoded it. `data` is owned by the result:
 * release it with fc_image_result_free. */
typedef struct fc_image_result {
    uint32_t width;
    uint32_t height;
    fc_image_format format;       /* the encoding of `data` (PNG, JPEG, EXR or RAW bytes, or an H.264 access unit:
                                     a RENDER's is an IDR frame decodable alone, a stream's see fc_client_subscribe) */
    fc_aov aov;                   /* what the image shows */
    float stage_ms[FC_STAGE_COUNT]; /* server-side duration of each stage; negative = not measured */
    uint8_t *data;                /* the encoded image bytes, exactly as received */
    size_t size;                  /* bytes in data */
} fc_image_result;

/* Connects to `host_port` — "HOST:PORT", "HOST" (port FC_DEFAULT_PORT), "[IPV6]:PORT",
 * "[IPV6]" (a bare IPv6 literal is refused: brackets, proto/PROTOCOL.md 1.1),
 * "unix:PATH" for a Unix-domain socket, or "srv:NAME" for one of the
 * daemons of a DNS SRV name (see fc_client_connect_session), each of the TCP
 * ones prefixed "tls://" for TLS (as options->tls) — sends HELLO (asking for
 * every capability this library has) and checks the WELCOME (protocol version 1). On success
 * *out is a new client the caller owns (fc_client_close releases it); on failure
 * *out is NULL. Errors: FC_ERR_USAGE for a malformed address, FC_ERR_CONNECT when
 * no address of the host accepts the connection in time, a server code (e.g.
 * FC_ERR_VERSION, FC_ERR_UNAUTHORIZED) when the server refuses the HELLO, FC_ERR_CLOSED /
 * FC_ERR_PROTOCOL / FC_ERR_IO when the handshake breaks. With TLS the server's
 * certificate must chain to options->tls_ca_file's CAs (or the system's) and
 * name the host connected to (sent as SNI; for "srv:" each target's name):
 * FC_ERR_TLS_UNKNOWN_CA, FC_ERR_TLS_NAME_MISMATCH, FC_ERR_TLS_EXPIRED otherwise;
 * FC_ERR_TLS_PLAINTEXT_PEER when the server answers in clear, FC_ERR_TLS_CLIENT_CERT
 * when it wants a client certificate it trusts, FC_ERR_TLS for anything else
 * (files that do not load). Without TLS, a daemon that wants it answers
 * FC_ERR_TLS_REQUIRED. */
FC_API fc_code fc_client_connect(const char *host_port, const fc_connect_options *options,
                                 fc_client **out, fc_error *err);

/* ---- Many daemons behind one DNS name ------------------------------------------
 * An address "srv:NAME" (e.g. "srv:_fluidcast._tcp.render.example.org") names the
 * DNS SRV records of NAME, one per daemon (target host and port, priority,
 * weight); a Kubernetes headless Service and any DNS server provide them. The
 * records are looked up with libresolv at each connect.
 *
 * fc_client_connect_session places the connection by `session`, the name the
 * caller will publish to or subscribe to: every client computes the same order
 * of the targets from the session name alone (rendezvous, or highest-random-
 * weight, hashing), so the producers and viewers of one session meet on one
 * daemon without any router, and adding or removing a daemon moves only the
 * sessions that daemon gains or loses (about 1/n of them). The order: lowest SRV
 * priority first; within a priority, by decreasing weight / -ln(u), u the score
 * below mapped into (0, 1) as (top 53 bits + 0.5) / 2^53 (with equal weights
 * simply by decreasing score; weight 0 counts as 0.01); ties by target name,
 * then port. The score of a session on a target is FNV-1a 64 over the session
 * name's bytes, one zero byte, the target name (no trailing dot), ':' and the port
 * in decimal, then MurmurHash3's 64-bit finaliser (fmix64). This is a contract:
 * libraries of any version and other implementations must place alike.
 * A target that cannot be reached (FC_ERR_CONNECT) gives way to the next in
 * this order, the same for every client of the session; any other failure
 * (a refused token, a broken handshake) is returned at once.
 *
 * Without a session (NULL or "", and fc_client_connect) an "srv:" address picks
 * as RFC 2782 says: lowest priority first, within it at random in proportion to
 * the weights, the next on FC_ERR_CONNECT.
 *
 * The SRV query goes to the DNS servers of /etc/resolv.conf, or, when the
 * environment variable FLUIDCAST_DNS_SERVER is set to "ADDR" or "ADDR:PORT"
 * (IPv4, port 53 by default), to that server alone: meant for tests and labs
 * that run their own DNS server. The targets' own addresses come from the
 * system resolver (getaddrinfo).
 *
 * Errors, besides those of fc_client_connect: FC_ERR_CONNECT when the name has
 * no SRV records, the DNS server does not answer, the only target is "."
 * (RFC 2782: no such service there), or no target can be reached (the message
 * names the last failure); FC_ERR_USAGE for "srv:" with no name or a malformed
 * FLUIDCAST_DNS_SERVER; FC_ERR_PROTOCOL for a DNS answer that does not parse.
 * Any other address behaves exactly as with fc_client_connect. */
FC_API fc_code fc_client_connect_session(const char *address, const char *session, const fc_connect_options *options,
                                         fc_client **out, fc_error *err);

/* The daemon this client is connected to: "HOST:PORT" as tried (for "srv:"
 * addresses the chosen target), or "unix:PATH". Owned by the client; valid
 * until fc_client_close. */
FC_API const char *fc_client_address(const fc_client *client);

/* Copies what the server announced at connect time into *out. Both pointers
 * must be valid; never fails. */
FC_API void fc_client_server_info(const fc_client *client, fc_server_info *out);

/* Sends a particle frame; it replaces the previous one on the server. Every
 * array the frame has travels (density, velocity, ids, radius; NULL = absent).
 * With frame->radius each particle is splatted at its own radius, unless the
 * settings' radius is > 0, which overrides them all (PROTOCOL.md 5). A server
 * that predates per-particle radii refuses such a frame with MALFORMED
 * ("unknown attribute bits 0x8"); send it again without radii for that server.
 * The server answers only when it rejects the frame (non-finite values, a
 * radius outside (0, 1e6], too many particles, more memory than the server
 * lets one connection hold): that ERROR is reported by the next
 * fc_client_render. The frame is not retained: its arrays go to the
 * socket from where the caller keeps them, without a copy, before this returns.
 * Errors: FC_ERR_TOO_LARGE (without sending) when the encoded frame exceeds the
 * server's message limit, FC_ERR_USAGE for an empty or NULL frame, plus the
 * connection errors. */
FC_API fc_code fc_client_send_frame(fc_client *client, const fc_frame *frame, fc_error *err);

/* Sends the camera for the following renders (image size included). Rejections
 * are reported by the next fc_client_render. */
FC_API fc_code fc_client_set_camera(fc_client *client, const fc_camera *camera, fc_error *err);

/* Sends the render settings for the following renders (fc_settings_default in
 * fc_settings.h gives a starting point). Rejections are reported by the next
 * fc_client_render. */
FC_API fc_code fc_client_set_settings(fc_client *client, const fc_settings *settings, fc_error *err);

/* ---- Scene images ----------------------------------------------------------
 * By default the server draws a floor and a sky behind the fluid and reflects a
 * procedural sky in it. A client may send its own images instead: PNG, JPEG or
 * EXR files, at most 8192 pixels per side. The server decodes them and keeps
 * them for this connection's later renders. Like settings, a rejection is
 * reported by the next fc_client_render: FC_ERR_INVALID_VALUE for bytes that do
 * not decode as such an image (or cube faces that are not square, or differ in
 * size or pixel format — all 8-bit or all float), FC_ERR_LIMIT for an image
 * larger than 8192 pixels per side or the GPU's texture size, or one that
 * decodes to more memory than the server lets one connection hold. Errors returned
 * directly: FC_ERR_TOO_LARGE (without sending) when the message exceeds the
 * server's message limit, FC_ERR_USAGE, plus the connection errors. */

/* Sends a background image, drawn behind the fluid and refracted through it
 * instead of the built-in floor and sky, stretched over the whole image: `size`
 * bytes of an image file. data NULL with size 0 goes back to the built-in scene. */
FC_API fc_code fc_client_set_background_bytes(fc_client *client, const void *data, size_t size, fc_error *err);

/* fc_client_set_background_bytes with the contents of the file at `path`
 * (NULL: back to the built-in scene). FC_ERR_IO naming the file when it cannot
 * be read, FC_ERR_USAGE when it is empty. */
FC_API fc_code fc_client_set_background_file(fc_client *client, const char *path, fc_error *err);

/* Sends an environment cube map, reflected in the fluid instead of the
 * procedural sky: six image files data[i] of sizes[i] bytes, in the order
 * +X, -X, +Y, -Y, +Z, -Z (OpenGL cube-map convention), square and of one size.
 * data and sizes NULL go back to the procedural sky. */
FC_API fc_code fc_client_set_environment_bytes(fc_client *client, const void *const data[6], const size_t sizes[6],
                                               fc_error *err);

/* fc_client_set_environment_bytes with the contents of six files, in the same
 * order (paths NULL: back to the procedural sky). FC_ERR_IO naming a file that
 * cannot be read, FC_ERR_USAGE for a NULL path or an empty file. */
FC_API fc_code fc_client_set_environment_files(fc_client *client, const char *const paths[6], fc_error *err);

/* ---- Meshes ----------------------------------------------------------------
 * Triangle meshes drawn with the fluid (PROTOCOL.md section 12): a tank, an
 * obstacle, a rigid body. Each has an id; sending a mesh of an id already sent
 * replaces it. The server draws opaque meshes (opacity 1) into the scene before
 * the fluid, which they hide where they are in front of it and which refracts
 * them; glass (opacity below 1) is blended over the fluid, tinting it. With
 * FC_MESH_HIDE_NEAR the faces turned toward the camera are not drawn, so a
 * tank's near walls do not hide the fluid in it. A producer's meshes (after
 * fc_client_publish) belong to its session and show in every viewer's images;
 * anyone else's belong to its connection. At most 64 meshes per connection,
 * 2^24 vertices and 2^24 triangles per mesh. Like settings, the server answers
 * only a rejection, which the next fc_client_render reports: FC_ERR_LIMIT for a
 * 65th mesh or one beyond the connection's memory limit, FC_ERR_BAD_STATE for
 * moving a mesh never sent. Errors returned directly, without sending:
 * FC_ERR_INVALID_VALUE for an index >= vertex_count (naming the triangle), a
 * vertex or normal that is not finite, a colour or opacity outside [0, 1];
 * FC_ERR_LIMIT beyond the counts above; FC_ERR_TOO_LARGE beyond the server's
 * message limit; FC_ERR_USAGE; plus the connection errors. */

/* Fills *mesh with no arrays, id 0, no flags, light grey (0.8), opacity 1 and
 * the identity transform: set the arrays and counts, then send it. */
FC_API void fc_mesh_defaults(fc_mesh *mesh);

/* Sends `mesh` (its arrays are copied into the message; the caller keeps them).
 * A mesh with triangle_count 0 and vertex_count 0 removes mesh `id`. */
FC_API fc_code fc_client_upload_mesh(fc_client *client, const fc_mesh *mesh, fc_error *err);

/* Removes mesh `id` (no error if there is none). */
FC_API fc_code fc_client_remove_mesh(fc_client *client, uint32_t id, fc_error *err);

/* Places meshes already sent anew, all in one message (a simulation's rigid
 * bodies, once per frame): `count` entries of distinct ids, at most 64. The
 * server moves all of them or, if one id was never sent, none. */
FC_API fc_code fc_client_move_meshes(fc_client *client, const fc_mesh_transform *entries, uint32_t count,
                                     fc_error *err);

/* Asks for an image of the current frame, camera and settings and waits for it.
 * On success *out holds the image (the caller frees it with fc_image_result_free).
 * On failure *out is empty (data NULL, size 0) and safe to free. When the server
 * rejected an earlier message of this client (a FRAME, CAMERA, SETTINGS, scene image or mesh) that
 * error is returned, since it is the cause, even if an image followed; the reply
 * to this request is consumed either way so the connection stays in step. */
FC_API fc_code fc_client_render(fc_client *client, const fc_render_request *request,
                                fc_image_result *out, fc_error *err);

/* Releases the image bytes and empties the result. Safe on an emptied result. */
FC_API void fc_image_result_free(fc_image_result *result);

/* Asks for the surface mesh of the frame a render would show now (the current
 * frame, or a session's newest) with the current settings (surface_cell,
 * surface_kernel, surface_smoothing) and waits for all of it (PROTOCOL.md 13).
 * `attributes` (FC_SURFACE_* bits) are the per-vertex attributes wanted; the
 * mesh has those the frame can give (out->attributes says which). On success
 * *out owns its arrays (free them with fc_surface_mesh_free) and *extract_ms
 * (may be NULL) is the server's extraction time, negative if not measured. On
 * failure *out is empty. Earlier rejections are returned as fc_client_render
 * does; a reply that breaks 13.3 is FC_ERR_PROTOCOL (the client is then closed
 * for further requests), with the receiver's verdict in the message. */
FC_API fc_code fc_client_extract_surface(fc_client *client, uint32_t attributes, fc_surface_mesh *out,
                                         float *extract_ms, fc_error *err);

/* Says GOODBYE to the server (best effort), closes the connection and frees the
 * client. NULL is ignored. */
FC_API void fc_client_close(fc_client *client);

/* ---- Sessions, streaming, multi-rank frames, packed uploads ----------------
 * A producer (a simulation) publishes frames to a named session; any number of
 * viewers subscribe to it and receive every frame the server renders for them,
 * each with its own camera, settings and image format. A viewer that reads too
 * slowly is sent the newest frame when it is ready again, with the number of
 * frames it missed: it never slows the producer or other viewers.
 *
 *     producer                                  viewer
 *     fc_client_publish(c, "dam", NULL, &e);    fc_client_subscribe(v, "dam", &req, 640, 360, NULL, &e);
 *     for each step:                            for (;;) {
 *         fc_client_upload_frame(c, &f, ...);       fc_client_next_image(v, &img, &e);
 *     fc_client_leave_session(c, &e);               if (img.ended) break;  ... fc_stream_image_free(&img);
 *                                               }
 *
 * A viewer may subscribe before any producer publishes: its SESSION_STATE
 * (fc_session_status) then says producers 0 and last_frame 0, and its first
 * image comes with the first frame. When the last producer leaves, the session
 * ends: the viewer gets an image with `ended` set, and stays on the session's
 * last frame until it leaves (PROTOCOL.md 10.1): fc_client_set_camera and
 * fc_client_set_settings still re-render that frame for it (`view_change`
 * images read with fc_client_next_image), so a finished run can be looked at
 * from every side. A new run published under the same name is a new session;
 * subscribing again (which leaves the ended one) watches it.
 *
 * A simulation split over K MPI ranks sends each frame as K chunks, one per
 * rank and connection (each rank publishes to the same session); the server
 * renders once all K chunks of a frame are in, concatenated in index order.
 *
 * These need a server that granted FC_SERVER_CAN_STREAM (see
 * fc_server_info.capabilities; fluidcastd 0.1 grants everything it has); a
 * call that needs a capability the server lacks returns FC_ERR_USAGE unsent. */

/* Capability bits of fc_server_info.capabilities. */
#define FC_SERVER_CAN_STREAM 0x1u       /* named sessions, streaming, multi-rank frames */
#define FC_SERVER_CAN_ZSTD 0x2u         /* zstd-compressed uploads */
#define FC_SERVER_CAN_QUANTIZE16 0x4u   /* 16-bit quantised positions */
#define FC_SERVER_CAN_DEVICE 0x8u       /* the server names its GPU device (fc_server_info.device) */

/* What the server says about a session. */
typedef struct fc_session_status {
    char name[65];               /* 1..64 bytes, NUL-terminated */
    uint32_t producers;          /* connections publishing to it */
    uint32_t viewers;            /* connections subscribed to it */
    uint64_t frames;             /* complete frames published so far */
    uint64_t last_frame;         /* frame number of the newest, 0 = none yet */
} fc_session_status;

/* Makes this connection a producer of session `name` (created when it does not
 * exist; several connections may publish to one session, e.g. the ranks of one
 * simulation). From then on fc_client_send_frame / fc_client_upload_frame
 * publish whole frames (numbered 1, 2, ...: the newest number + 1), and
 * fc_client_send_chunk parts of frames; fc_client_render renders the session's
 * newest complete frame. Waits for the server's answer; *status (may be NULL)
 * receives the session's state. Errors: FC_ERR_BAD_STATE when the connection
 * is in a session already, FC_ERR_INVALID_VALUE / FC_ERR_USAGE for a name not
 * of 1..64 bytes, FC_ERR_LIMIT when the server holds its maximum of sessions. */
FC_API fc_code fc_client_publish(fc_client *client, const char *name, fc_session_status *status, fc_error *err);

/* Makes this connection a viewer of session `name` (which need not have a
 * producer yet). Every frame published from now on is rendered for it with its
 * camera (fc_client_set_camera; until one is sent, each frame is framed
 * automatically at width x height, 0 x 0 for the server's default 1280x720) and
 * settings, in `format` (format, quality and aov as for fc_client_render), and
 * read with fc_client_next_image. When it uses JPEG or H.264, a lossless PNG of
 * the last frame follows once nothing has changed for a while (server option
 * --refresh-ms, flag `refresh`).
 *
 * FC_FORMAT_H264 makes the images a video stream (PROTOCOL.md 10.7): each
 * image's data is one H.264 access unit in Annex B byte-stream format, handed
 * over unchanged, to be fed in order to one decoder (libavcodec's h264, for
 * instance) that starts at a key frame: the first image is one (`keyframe`,
 * an IDR frame with its SPS and PPS), and so is the first after a change of
 * size. Frames the server skipped (`missed`) were never encoded, so the
 * stream stays decodable; an image this library dropped while waiting for
 * another reply was, so it asks the server for a key frame then
 * (fc_client_request_keyframe) and the images before it may decode with
 * errors. REFRESH images are PNG files, not part of the stream. H.264 needs
 * an even width and height. Changing camera or settings re-renders the current frame.
 * fc_client_render still works: it renders the session's newest frame and its
 * image is never dropped. Errors as for fc_client_publish, plus those of a
 * RENDER for the format and FC_ERR_LIMIT for a size beyond the server's. */
FC_API fc_code fc_client_subscribe(fc_client *client, const char *name, const fc_render_request *format,
                                   uint32_t width, uint32_t height, fc_session_status *status, fc_error *err);

/* One image of a subscribed session. */
typedef struct fc_stream_image {
    fc_image_result image;       /* the encoded image, as fc_client_render returns it; empty when ended */
    uint64_t frame_number;       /* the producer's number of the frame shown */
    uint64_t sequence;           /* 1-based count of frames the session published up to this one */
    uint32_t missed;             /* frames published since this viewer's previous image that it never got */
    int refresh;                 /* nonzero: a lossless copy of a frame already shown lossy */
    int view_change;             /* nonzero: the same frame again, after this viewer's camera/settings changed */
    int ended;                   /* nonzero: the session is over (its producers left); no image in this one.
                                    The viewer stays on the last frame: after it only view_change images
                                    (and their refresh) follow, made by its own camera/settings changes */
    int keyframe;                /* H.264: nonzero when the access unit is an IDR frame (a decoder may start) */
} fc_stream_image;

/* Waits for the next image of the subscribed session (or its end). Stream
 * images that arrive while this client waits for another reply (a render, a
 * session list) are dropped, and counted in the next image's `missed`. The
 * reply timeout of fc_connect_options bounds the wait. Errors: FC_ERR_USAGE
 * when not subscribed; a server code when the server rejected an earlier
 * request of this client (e.g. a CAMERA) or could not render an image for this
 * viewer (the subscription stays either way); the connection errors. */
FC_API fc_code fc_client_next_image(fc_client *client, fc_stream_image *out, fc_error *err);

/* Waits at most timeout_ms (0: not at all) for the server to send this client
 * something, such as the subscribed session's next image; *ready becomes
 * nonzero when there is input to read (or the connection was closed, which the
 * next read reports). A viewer calls it between its camera changes, so that it
 * can send them while a slow producer's next frame is still to come, and calls
 * fc_client_next_image once it is ready. Errors: FC_ERR_USAGE for a NULL ready;
 * FC_ERR_CLOSED on a client already broken. */
FC_API fc_code fc_client_wait_input(fc_client *client, uint32_t timeout_ms, int *ready, fc_error *err);
FC_API void fc_stream_image_free(fc_stream_image *image);

/* Asks the server to make this viewer's next H.264 image a key frame (an
 * empty SETTINGS): the current frame comes again as an IDR frame, flagged
 * `view_change` and `keyframe`, after the image already in flight. For a
 * decoder that lost its place. Other formats just get the current frame
 * again. FC_ERR_USAGE when not subscribed; the connection errors. */
FC_API fc_code fc_client_request_keyframe(fc_client *client, fc_error *err);

/* Leaves the session: a producer stops publishing (the session ends for its
 * viewers once its last producer has left or disconnected), a viewer stops
 * receiving images, also a viewer of a session that ended (which the server
 * frees once its last viewer has left). Waits until the server confirms, so no
 * image of the session arrives after it. FC_ERR_BAD_STATE when the connection is in no session; an
 * error the server reported for an earlier request of this client (e.g. a
 * chunk) is returned like fc_client_render does, after the confirmation. */
FC_API fc_code fc_client_leave_session(fc_client *client, fc_error *err);

/* Nonzero when this client is a viewer whose session ended (its `ended` image
 * was read, or arrived while waiting for another reply): it still watches the
 * session's last frame. 0 otherwise, also for NULL. */
FC_API int fc_client_session_ended(const fc_client *client);

/* The server's live sessions, oldest first: *sessions (free it with
 * fc_session_list_free) gets *count entries. */
FC_API fc_code fc_client_list_sessions(fc_client *client, fc_session_status **sessions, uint32_t *count, fc_error *err);
FC_API void fc_session_list_free(fc_session_status *sessions);

/* How a frame travels (fc_client_upload_frame, fc_client_send_chunk). */
#define FC_UPLOAD_ZSTD 0x1u          /* zstd-compress the particle data (lossless) */
#define FC_UPLOAD_QUANTIZE16 0x2u    /* positions as 16-bit offsets in the frame's bounding box: each
                                        coordinate is off by at most (box extent / 65535 / 2);
                                        densities, velocities, ids and radii travel exact */

typedef struct fc_upload_options {
    uint32_t encoding;           /* FC_UPLOAD_* bits; 0 = plain floats, uncompressed */
    int zstd_level;              /* zstd compression level; 0 = 3 */
} fc_upload_options;

/* What one upload cost. */
typedef struct fc_upload_stats {
    uint64_t raw_bytes;          /* bytes the frame takes as a plain, uncompressed message */
    uint64_t wire_bytes;         /* bytes actually sent */
} fc_upload_stats;

/* Sends a frame like fc_client_send_frame, encoded as `options` says (NULL:
 * plain). *stats (may be NULL) receives the bytes it took. Errors as for
 * fc_client_send_frame, plus FC_ERR_USAGE for an encoding the server did not
 * grant or, with FC_UPLOAD_QUANTIZE16, non-finite positions. */
FC_API fc_code fc_client_upload_frame(fc_client *client, const fc_frame *frame, const fc_upload_options *options,
                                      fc_upload_stats *stats, fc_error *err);

/* Sends chunk `index` of `count` (K) of frame `frame_number` of the session
 * this connection publishes to: `part` holds this rank's particles. Every
 * chunk of a frame must carry the same K and attributes. The server answers
 * only a rejection, reported by the next waiting call (or fc_client_poll_errors),
 * with these codes: FC_ERR_INVALID_VALUE for K = 0, K > 4096 or index >= K;
 * FC_ERR_DUPLICATE for an index of the frame sent before; FC_ERR_INCONSISTENT
 * when K or the attributes differ from the frame's first chunk; FC_ERR_INCOMPLETE
 * (to every rank that sent a chunk) when the frame still lacks chunks after the
 * server's chunk timeout; FC_ERR_BAD_STATE without fc_client_publish. */
FC_API fc_code fc_client_send_chunk(fc_client *client, uint64_t frame_number, uint32_t index, uint32_t count,
                                    const fc_frame *part, const fc_upload_options *options, fc_upload_stats *stats,
                                    fc_error *err);

/* Reads whatever the server has sent without waiting: returns the first server
 * ERROR (its code; the connection stays usable), FC_OK when there is none.
 * For producers that only send and want to hear about rejected chunks. */
FC_API fc_code fc_client_poll_errors(fc_client *client, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
