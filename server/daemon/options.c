/* options.c — fluidcastd's command line: defaults, parsing, --help. */
#include "options.h"

#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "image_encoder.h"
#include "fc_error.h"
#include "fc_options.h"

enum { MAX_ENCODERS = 64 };

/* Whole-string unsigned decimal within [min, max] (min 0 or 1). */
static fc_code parse_number(const char *option, const char *text, uint64_t min, uint64_t max, uint64_t *out,
                            fc_error *err)
{
    char *end = NULL;
    errno = 0;
    unsigned long long value = strtoull(text, &end, 10);
    if (text[0] < '0' || text[0] > '9' || *end != '\0' || errno == ERANGE || value < min || value > max)
        return fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected a whole number from %" PRIu64 " to %" PRIu64,
                            option, text, min, max);
    *out = value;
    return FC_OK;
}

static fc_code parse_u32(const char *option, const char *text, uint64_t min, uint64_t max, uint32_t *out,
                         fc_error *err)
{
    uint64_t n = 0;
    fc_code code = parse_number(option, text, min, max, &n, err);
    if (code == FC_OK)
        *out = (uint32_t)n;
    return code;
}

static fc_daemon_options *as_options(void *target)
{
    return target;
}

static fc_code set_listen(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    as_options(o)->listen_given = true;
    return fc_daemon_options_parse_listen(value, o, err);
}

static fc_code set_gpu(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return fc_gpu_choice_parse(value, &as_options(o)->gpu, err);
}

static fc_code set_log_level(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return fc_log_level_parse(value, &as_options(o)->log_level, err);
}

static fc_code set_shader_dir(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->shader_dir = value;
    return FC_OK;
}

static fc_code set_port_file(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->port_file = value;
    return FC_OK;
}

static fc_code set_unix(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->unix_path = value;
    return FC_OK;
}

static fc_code set_token_file(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->token_file = value;
    return FC_OK;
}

static fc_code set_tls_cert(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->tls_cert = value;
    return FC_OK;
}

static fc_code set_metrics_tls(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    as_options(o)->metrics_tls = true;
    return FC_OK;
}

static fc_code set_tls_key(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->tls_key = value;
    return FC_OK;
}

static fc_code set_tls_client_ca(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->tls_client_ca = value;
    return FC_OK;
}

static fc_code set_tls_handshake_timeout(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 1, UINT32_MAX, &as_options(o)->tls_handshake_timeout_ms, err);
}

static fc_code set_metrics_listen(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return fc_daemon_options_parse_metrics_listen(value, o, err);
}

static fc_code set_web_listen(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return fc_daemon_options_parse_web_listen(value, o, err);
}

static fc_code set_max_particles(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_number(name, value, 1, UINT64_MAX, &as_options(o)->limits.max_particles, err);
}

static fc_code set_max_image(void *o, const char *name, const char *value, fc_error *err)
{
    const char *x = strchr(value, 'x');
    char width[32];
    if (!x || (size_t)(x - value) >= sizeof width)
        return fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected WIDTHxHEIGHT, e.g. 4096x4096", name, value);
    memcpy(width, value, (size_t)(x - value));
    width[x - value] = '\0';
    fc_limits *limits = &as_options(o)->limits;
    if (parse_u32("--max-image width", width, 1, UINT32_MAX, &limits->max_width, err) != FC_OK)
        return FC_ERR_USAGE;
    return parse_u32("--max-image height", x + 1, 1, UINT32_MAX, &limits->max_height, err);
}

static fc_code set_max_message(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 1, UINT32_MAX, &as_options(o)->limits.max_message, err);
}

static fc_code set_chunk_timeout(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 1, UINT32_MAX, &as_options(o)->chunk_timeout_ms, err);
}

static fc_code set_refresh(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 0, UINT32_MAX, &as_options(o)->refresh_ms, err);
}

static fc_code set_encoders(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 1, MAX_ENCODERS, &as_options(o)->encoders, err);
}

static fc_code set_png_compression(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 0, FC_PNG_MAX_COMPRESSION, &as_options(o)->png_compression, err);
}

static fc_code set_max_sessions(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 1, UINT32_MAX, &as_options(o)->max_sessions, err);
}

static fc_code set_max_connections(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 1, UINT32_MAX, &as_options(o)->max_connections, err);
}

static fc_code set_idle_timeout(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 0, UINT32_MAX, &as_options(o)->idle_timeout_ms, err);
}

static fc_code set_read_timeout(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_u32(name, value, 0, UINT32_MAX, &as_options(o)->read_timeout_ms, err);
}

static fc_code set_max_session_memory(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_number(name, value, 1, UINT64_MAX, &as_options(o)->max_session_memory, err);
}

/* Every option: its flag, value, help and default, in the order --help lists them. */
static const fc_option options[] = {
    {"--listen", "HOST:PORT", set_listen,
     "address to listen on; [ADDR]:PORT for IPv6, port 0 = any free port", FC_DEFAULT_SERVER},
    {"--gpu", "auto|software|N|cuda:N", set_gpu,
     "auto: the first GPU EGL device that initialises, else Mesa llvmpipe, logging why; software: llvmpipe; "
     "N: EGL device number N; cuda:N: the GPU that CUDA numbers N (NVIDIA, EGL_NV_device_cuda), as Slurm and "
     "Kubernetes hand them out", "auto"},
    {"--log-level", "LEVEL", set_log_level, "error, warn, info or debug", "info"},
    {"--shader-dir", "DIR", set_shader_dir,
     "load the *.glsl shaders from DIR instead of the built-in copies (development)", NULL},
    {"--port-file", "PATH", set_port_file, "write the bound port to PATH once listening", NULL},
    {"--max-particles", "N", set_max_particles, "particles per frame", "16777216"},
    {"--max-image", "WxH", set_max_image, "largest image", "8192x8192"},
    {"--max-message", "BYTES", set_max_message, "largest message payload", "1073741824"},
    {"--unix", "PATH", set_unix,
     "also listen on the Unix-domain socket PATH; alone (without --listen) only there", NULL},
    {"--chunk-timeout-ms", "MS", set_chunk_timeout,
     "how long a multi-rank frame may wait for its missing chunks before they are reported incomplete", "10000"},
    {"--refresh-ms", "MS", set_refresh,
     "quiet time after a JPEG or H.264 stream image before a lossless PNG refresh of the same frame follows; "
     "0 = never", "1000"},
    {"--encoders", "N", set_encoders, "image encoder threads (default min(4, cores))", NULL},
    {"--png-compression", "N", set_png_compression,
     "PNG's zlib level: 0 (fastest, largest) .. 9 (smallest, slowest); each image is deflated in strips on up "
     "to 8 cores", FC_STRINGIFY(FC_PNG_DEFAULT_COMPRESSION)},
    {"--max-sessions", "N", set_max_sessions, "named sessions at once", "256"},
    {"--max-connections", "N", set_max_connections,
     "client connections at once; more are answered with ERROR LIMIT and closed", "1024"},
    {"--idle-timeout-ms", "MS", set_idle_timeout,
     "close a connection that completed no message for this long (viewers excepted); 0 = never", "300000"},
    {"--read-timeout-ms", "MS", set_read_timeout,
     "a message whose first bytes arrived must be complete within this, or the connection is closed; "
     "0 = never", "30000"},
    {"--max-session-memory", "BYTES", set_max_session_memory,
     "bytes one connection may hold: its frame, scene images and unsent replies, and for a producer its "
     "session's frame and the multi-rank frames being assembled; a message beyond it gets ERROR LIMIT",
     "4294967296"},
    {"--metrics-listen", "ADDR", set_metrics_listen,
     "serve /metrics (Prometheus), /healthz and /readyz over HTTP on ADDR: HOST:PORT, [ADDR]:PORT or PORT "
     "alone (then on " FC_DEFAULT_HOST "); never on a render port; none by default", NULL},
    {"--web-listen", "ADDR", set_web_listen,
     "serve the web viewer (a page, and a WebSocket speaking the fluidcast protocol, docs/web.md) over HTTP on ADDR: "
     "HOST:PORT, [ADDR]:PORT or PORT alone (then on " FC_DEFAULT_HOST "); none by default", NULL},
    {"--token-file", "PATH", set_token_file,
     "require clients to send the token in PATH (one line) in HELLO; without it the FLUIDCAST_TOKEN "
     "environment variable, if set, is the token", NULL},
    {"--tls-cert", "PATH", set_tls_cert,
     "serve TLS (1.3, 1.2 at least) on every TCP listener with this PEM certificate chain; SIGHUP reloads it "
     "and the key for new connections; Unix sockets stay in clear", NULL},
    {"--tls-key", "PATH", set_tls_key, "the PEM private key of --tls-cert", NULL},
    {"--tls-client-ca", "PATH", set_tls_client_ca,
     "mutual TLS: clients must present a certificate issued by a CA in this PEM file", NULL},
    {"--metrics-tls", NULL, set_metrics_tls,
     "serve --metrics-listen over HTTPS with the --tls-cert certificate and key (read once, at the start; "
     "restart the daemon to rotate them there)", NULL},
    {"--tls-handshake-timeout-ms", "MS", set_tls_handshake_timeout,
     "a TLS handshake not complete within this is dropped (counted in /metrics)", "10000"},
};

static const fc_option_table table = {"fluidcastd", options, sizeof options / sizeof options[0], NULL, NULL};

fc_code fc_daemon_options_default(fc_daemon_options *o, fc_error *err)
{
    memset(o, 0, sizeof *o);
    fc_code code = fc_options_set_defaults(&table, o, err);
    o->listen_given = false;   /* the default address is not a --listen given */
    return code;
}

fc_code fc_daemon_options_check_tls(const fc_daemon_options *o, fc_error *err)
{
    if (!o->tls_cert != !o->tls_key)
        return fc_error_set(err, FC_ERR_USAGE, "--tls-cert and --tls-key go together");
    if (o->tls_client_ca && !o->tls_cert)
        return fc_error_set(err, FC_ERR_USAGE, "--tls-client-ca needs --tls-cert and --tls-key");
    if (o->metrics_tls && !o->tls_cert)
        return fc_error_set(err, FC_ERR_USAGE, "--metrics-tls needs --tls-cert and --tls-key");
    return FC_OK;
}

bool fc_daemon_options_serve_tcp(const fc_daemon_options *o)
{
    return o->listen_given || !o->unix_path;
}

void fc_daemon_options_print_help(FILE *out, const char *program)
{
    fprintf(out,
            "usage: %s [options]\n"
            "Headless render daemon: receives particle frames and cameras over TCP or a\n"
            "Unix-domain socket and answers with screen-space fluid renderings; streams\n"
            "the frames of named sessions to any number of viewers.\n"
            "\n",
            program);
    fc_options_print_help(out, &table);
    fprintf(out,
            "\n"
            "Without a token anyone who can reach the port can use the daemon: listening\n"
            "beyond loopback without one prints a warning. Without --tls-cert everything,\n"
            "the token included, travels in clear: listening beyond loopback without TLS\n"
            "prints a warning too.\n"
            "A render that fails on the GPU (out of memory, a GL error, a lost context) is\n"
            "answered with ERROR RENDER; the daemon then rebuilds its pipeline or recreates\n"
            "its GL context, and keeps serving.\n"
            "SIGINT or SIGTERM stops the daemon cleanly (exit status 0).\n"
            "Under systemd (deploy/systemd): readiness and stopping are announced with\n"
            "sd_notify (Type=notify), and sockets passed by socket activation (LISTEN_FDS)\n"
            "are served instead of --listen and --unix.\n");
}

fc_code fc_daemon_options_parse_listen(const char *text, fc_daemon_options *o, fc_error *err)
{
    static const fc_host_port_rules rules = {"--listen", FC_DEFAULT_PORT, true};
    return fc_host_port_parse(text, &rules, o->listen_host, o->listen_port, err);
}

/* A side listener's ADDR (--metrics-listen, --web-listen): PORT alone is that
 * port on FC_DEFAULT_HOST; any other address needs its port: the default port
 * is the render port, which a side listener must never share. */
static fc_code parse_side_listen(const fc_host_port_rules *rules, const char *text, char *host, char *port,
                                 fc_error *err)
{
    char address[FC_HOST_MAX + FC_PORT_MAX + 8];
    if (text[0] != '\0' && strspn(text, "0123456789") == strlen(text) && strlen(text) < FC_PORT_MAX + 2) {
        snprintf(address, sizeof address, "%s:%s", FC_DEFAULT_HOST, text);
        text = address;
    }
    return fc_host_port_parse(text, rules, host, port, err);
}

fc_code fc_daemon_options_parse_metrics_listen(const char *text, fc_daemon_options *o, fc_error *err)
{
    static const fc_host_port_rules rules = {"--metrics-listen", 0, true};
    return parse_side_listen(&rules, text, o->metrics_host, o->metrics_port, err);
}

fc_code fc_daemon_options_parse_web_listen(const char *text, fc_daemon_options *o, fc_error *err)
{
    static const fc_host_port_rules rules = {"--web-listen", 0, true};
    return parse_side_listen(&rules, text, o->web_host, o->web_port, err);
}

fc_code fc_daemon_options_parse(int argc, char **argv, fc_daemon_options *o, fc_error *err)
{
    fc_code code = fc_options_parse(&table, argc - 1, argv + 1, o, &o->help, err);
    return code == FC_OK ? fc_daemon_options_check_tls(o, err) : code;
}
