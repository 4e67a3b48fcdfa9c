/* options.c — fluidcastd's command line: defaults, parsing, --help. */
#include "options.h"

#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "image_encoder.h"
#include "fc_error.h"

enum { MAX_ENCODERS = 64 };

void fc_daemon_options_default(fc_daemon_options *o)
{
    memset(o, 0, sizeof *o);
    snprintf(o->listen_host, sizeof o->listen_host, "%s", FC_DEFAULT_HOST);
    snprintf(o->listen_port, sizeof o->listen_port, "%d", FC_DEFAULT_PORT);
    o->gpu.mode = FC_GPU_AUTO;
    o->log_level = FC_LOG_INFO;
    o->limits.max_particles = FC_DEFAULT_MAX_PARTICLES;
    o->limits.max_width = FC_DEFAULT_MAX_IMAGE_SIDE;
    o->limits.max_height = FC_DEFAULT_MAX_IMAGE_SIDE;
    o->limits.max_message = FC_DEFAULT_MAX_MESSAGE;
    o->chunk_timeout_ms = FC_DEFAULT_CHUNK_TIMEOUT_MS;
    o->refresh_ms = FC_DEFAULT_REFRESH_MS;
    o->png_compression = FC_PNG_DEFAULT_COMPRESSION;
    o->max_sessions = FC_DEFAULT_MAX_SESSIONS;
    o->max_connections = FC_DEFAULT_MAX_CONNECTIONS;
    o->idle_timeout_ms = FC_DEFAULT_IDLE_TIMEOUT_MS;
    o->read_timeout_ms = FC_DEFAULT_READ_TIMEOUT_MS;
    o->max_session_memory = FC_DEFAULT_MAX_SESSION_MEMORY;
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
            "\n"
            "  --listen HOST:PORT      address to listen on; [ADDR]:PORT for IPv6, port 0 = any\n"
            "                          free port (default %s:%d)\n"
            "  --gpu auto|software|N|cuda:N\n"
            "                          auto: the first GPU EGL device that initialises, else\n"
            "                          Mesa llvmpipe, logging why; software: llvmpipe; N: EGL\n"
            "                          device number N; cuda:N: the GPU that CUDA numbers N\n"
            "                          (NVIDIA, EGL_NV_device_cuda), as Slurm and Kubernetes\n"
            "                          hand them out (default auto)\n"
            "  --log-level LEVEL       error, warn, info or debug (default info)\n"
            "  --shader-dir DIR        load the *.glsl shaders from DIR instead of the built-in\n"
            "                          copies (development)\n"
            "  --port-file PATH        write the bound port to PATH once listening\n"
            "  --max-particles N       particles per frame (default %u)\n"
            "  --max-image WxH         largest image (default %ux%u)\n"
            "  --max-message BYTES     largest message payload (default %u)\n"
            "  --unix PATH             also listen on the Unix-domain socket PATH; alone\n"
            "                          (without --listen) only there\n"
            "  --chunk-timeout-ms MS   how long a multi-rank frame may wait for its missing\n"
            "                          chunks before they are reported incomplete (default %u)\n"
            "  --refresh-ms MS         quiet time after a JPEG or H.264 stream image before a\n"
            "                          lossless PNG refresh of the same frame follows; 0 = never\n"
            "                          (default %u)\n"
            "  --encoders N            image encoder threads (default min(4, cores))\n"
            "  --png-compression N     PNG's zlib level: 0 (fastest, largest) .. 9 (smallest,\n"
            "                          slowest) (default %u); each image is deflated in\n"
            "                          strips on up to 8 cores\n"
            "  --max-sessions N        named sessions at once (default %u)\n"
            "  --max-connections N     client connections at once; more are answered with\n"
            "                          ERROR LIMIT and closed (default %u)\n"
            "  --idle-timeout-ms MS    close a connection that completed no message for this\n"
            "                          long (viewers excepted); 0 = never (default %u)\n"
            "  --read-timeout-ms MS    a message whose first bytes arrived must be complete\n"
            "                          within this, or the connection is closed; 0 = never\n"
            "                          (default %u)\n"
            "  --max-session-memory BYTES\n"
            "                          bytes one connection may hold: its frame, scene images\n"
            "                          and unsent replies, and for a producer its session's\n"
            "                          frame and the multi-rank frames being assembled; a\n"
            "                          message beyond it gets ERROR LIMIT (default %llu)\n"
            "  --metrics-listen ADDR   serve /metrics (Prometheus), /healthz and /readyz over\n"
            "                          HTTP on ADDR: HOST:PORT, [ADDR]:PORT or PORT alone\n"
            "                          (then on 127.0.0.1); never on a render port (default:\n"
            "                          none)\n"
            "  --token-file PATH       require clients to send the token in PATH (one line)\n"
            "                          in HELLO; without it the FLUIDCAST_TOKEN environment\n"
            "                          variable, if set, is the token\n"
            "  --help                  show this help\n"
            "\n"
            "Without a token anyone who can reach the port can use the daemon: listening\n"
            "beyond loopback without one prints a warning.\n"
            "A render that fails on the GPU (out of memory, a GL error, a lost context) is\n"
            "answered with ERROR RENDER; the daemon then rebuilds its pipeline or recreates\n"
            "its GL context, and keeps serving.\n"
            "SIGINT or SIGTERM stops the daemon cleanly (exit status 0).\n"
            "Under systemd (deploy/systemd): readiness and stopping are announced with\n"
            "sd_notify (Type=notify), and sockets passed by socket activation (LISTEN_FDS)\n"
            "are served instead of --listen and --unix.\n",
            program, FC_DEFAULT_HOST, FC_DEFAULT_PORT, FC_DEFAULT_MAX_PARTICLES,
            FC_DEFAULT_MAX_IMAGE_SIDE, FC_DEFAULT_MAX_IMAGE_SIDE, FC_DEFAULT_MAX_MESSAGE,
            FC_DEFAULT_CHUNK_TIMEOUT_MS, FC_DEFAULT_REFRESH_MS, FC_PNG_DEFAULT_COMPRESSION, FC_DEFAULT_MAX_SESSIONS,
            FC_DEFAULT_MAX_CONNECTIONS, FC_DEFAULT_IDLE_TIMEOUT_MS, FC_DEFAULT_READ_TIMEOUT_MS,
            (unsigned long long)FC_DEFAULT_MAX_SESSION_MEMORY);
}

/* Whole-string unsigned decimal within [1, max]. */
static fc_code parse_count(const char *option, const char *text, uint64_t max, uint64_t *out, fc_error *err)
{
    *out = 0;
    char *end = NULL;
    errno = 0;
    unsigned long long value = strtoull(text, &end, 10);
    if (text[0] < '0' || text[0] > '9' || *end != '\0' || errno == ERANGE || value < 1 || value > max)
        return fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected a whole number from 1 to %" PRIu64, option,
                            text, max);
    *out = value;
    return FC_OK;
}

static fc_code parse_image_size(const char *text, fc_limits *limits, fc_error *err)
{
    const char *x = strchr(text, 'x');
    char width[32];
    if (!x || (size_t)(x - text) >= sizeof width)
        return fc_error_set(err, FC_ERR_USAGE, "--max-image '%s': expected WIDTHxHEIGHT, e.g. 4096x4096", text);
    memcpy(width, text, (size_t)(x - text));
    width[x - text] = '\0';
    uint64_t w, h;
    if (parse_count("--max-image width", width, UINT32_MAX, &w, err) != FC_OK ||
        parse_count("--max-image height", x + 1, UINT32_MAX, &h, err) != FC_OK)
        return FC_ERR_USAGE;
    limits->max_width = (uint32_t)w;
    limits->max_height = (uint32_t)h;
    return FC_OK;
}

fc_code fc_daemon_options_parse_listen(const char *text, fc_daemon_options *o, fc_error *err)
{
    static const fc_host_port_rules rules = {"--listen", FC_DEFAULT_PORT, true};
    return fc_host_port_parse(text, &rules, o->listen_host, o->listen_port, err);
}

/* A port alone is one on FC_DEFAULT_HOST; any other address needs its port:
 * the default port is the render port, which the metrics must never share. */
fc_code fc_daemon_options_parse_metrics_listen(const char *text, fc_daemon_options *o, fc_error *err)
{
    static const fc_host_port_rules rules = {"--metrics-listen", 0, true};
    char address[FC_HOST_MAX + FC_PORT_MAX + 8];
    if (text[0] != '\0' && strspn(text, "0123456789") == strlen(text) && strlen(text) < FC_PORT_MAX + 2) {
        snprintf(address, sizeof address, "%s:%s", FC_DEFAULT_HOST, text);
        text = address;
    }
    return fc_host_port_parse(text, &rules, o->metrics_host, o->metrics_port, err);
}

static bool is_known_option(const char *name)
{
    static const char *const known[] = {"--listen",        "--gpu",       "--log-level",  "--shader-dir",
                                        "--port-file",     "--max-particles", "--max-image", "--max-message",
                                        "--unix",          "--chunk-timeout-ms", "--refresh-ms", "--encoders",
                                        "--max-sessions", "--max-connections", "--idle-timeout-ms",
                                        "--read-timeout-ms", "--token-file", "--max-session-memory",
                                        "--png-compression", "--metrics-listen"};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (strcmp(name, known[i]) == 0)
            return true;
    return false;
}

/* Whole-string unsigned decimal within [0, max]. */
static fc_code parse_ms(const char *option, const char *text, uint32_t *out, fc_error *err)
{
    uint64_t n;
    if (strcmp(text, "0") == 0) {
        *out = 0;
        return FC_OK;
    }
    if (parse_count(option, text, UINT32_MAX, &n, err) != FC_OK)
        return FC_ERR_USAGE;
    *out = (uint32_t)n;
    return FC_OK;
}

/* Applies one of the options of authentication and per-connection limits. */
static fc_code apply_hardening_option(const char *name, const char *value, fc_daemon_options *o, fc_error *err)
{
    uint64_t n;
    if (strcmp(name, "--token-file") == 0) {
        o->token_file = value;
        return FC_OK;
    }
    if (strcmp(name, "--metrics-listen") == 0)
        return fc_daemon_options_parse_metrics_listen(value, o, err);
    if (strcmp(name, "--max-connections") == 0) {
        if (parse_count(name, value, UINT32_MAX, &n, err) != FC_OK)
            return FC_ERR_USAGE;
        o->max_connections = (uint32_t)n;
        return FC_OK;
    }
    if (strcmp(name, "--idle-timeout-ms") == 0)
        return parse_ms(name, value, &o->idle_timeout_ms, err);
    if (strcmp(name, "--read-timeout-ms") == 0)
        return parse_ms(name, value, &o->read_timeout_ms, err);
    if (strcmp(name, "--max-session-memory") == 0)
        return parse_count(name, value, UINT64_MAX, &o->max_session_memory, err);
    return fc_error_set(err, FC_ERR_USAGE, "unknown option '%s' (see --help)", name);
}

/* Applies one of the options of sessions and streaming. */
static fc_code apply_stream_option(const char *name, const char *value, fc_daemon_options *o, fc_error *err)
{
    uint64_t n = 0;
    if (strcmp(name, "--unix") == 0) {
        o->unix_path = value;
        return FC_OK;
    }
    if (strcmp(name, "--chunk-timeout-ms") == 0) {
        if (parse_count(name, value, UINT32_MAX, &n, err) != FC_OK)
            return FC_ERR_USAGE;
        o->chunk_timeout_ms = (uint32_t)n;
        return FC_OK;
    }
    if (strcmp(name, "--refresh-ms") == 0)
        return parse_ms(name, value, &o->refresh_ms, err);
    if (strcmp(name, "--encoders") == 0) {
        if (parse_count(name, value, MAX_ENCODERS, &n, err) != FC_OK)
            return FC_ERR_USAGE;
        o->encoders = (uint32_t)n;
        return FC_OK;
    }
    if (strcmp(name, "--png-compression") == 0) {
        if (strcmp(value, "0") != 0 && parse_count(name, value, FC_PNG_MAX_COMPRESSION, &n, err) != FC_OK)
            return fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected a whole number from 0 to %u", name, value,
                                FC_PNG_MAX_COMPRESSION);
        o->png_compression = (uint32_t)n;
        return FC_OK;
    }
    if (strcmp(name, "--max-sessions") == 0) {
        if (parse_count(name, value, UINT32_MAX, &n, err) != FC_OK)
            return FC_ERR_USAGE;
        o->max_sessions = (uint32_t)n;
        return FC_OK;
    }
    return apply_hardening_option(name, value, o, err);
}

/* Applies one option that takes a value. */
static fc_code apply_option(const char *name, const char *value, fc_daemon_options *o, fc_error *err)
{
    uint64_t n;
    if (strcmp(name, "--listen") == 0) {
        o->listen_given = true;
        return fc_daemon_options_parse_listen(value, o, err);
    }
    if (strcmp(name, "--gpu") == 0)
        return fc_gpu_choice_parse(value, &o->gpu, err);
    if (strcmp(name, "--log-level") == 0)
        return fc_log_level_parse(value, &o->log_level, err);
    if (strcmp(name, "--shader-dir") == 0) {
        o->shader_dir = value;
        return FC_OK;
    }
    if (strcmp(name, "--port-file") == 0) {
        o->port_file = value;
        return FC_OK;
    }
    if (strcmp(name, "--max-particles") == 0) {
        if (parse_count(name, value, UINT64_MAX, &n, err) != FC_OK)
            return FC_ERR_USAGE;
        o->limits.max_particles = n;
        return FC_OK;
    }
    if (strcmp(name, "--max-image") == 0)
        return parse_image_size(value, &o->limits, err);
    if (strcmp(name, "--max-message") == 0) {
        if (parse_count(name, value, UINT32_MAX, &n, err) != FC_OK)
            return FC_ERR_USAGE;
        o->limits.max_message = (uint32_t)n;
        return FC_OK;
    }
    return apply_stream_option(name, value, o, err);
}

fc_code fc_daemon_options_parse(int argc, char **argv, fc_daemon_options *o, fc_error *err)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            o->help = true;
            continue;
        }
        char name[64];
        const char *equals = strchr(arg, '=');
        size_t name_len = equals ? (size_t)(equals - arg) : strlen(arg);
        if (name_len < sizeof name) {
            memcpy(name, arg, name_len);
            name[name_len] = '\0';
        }
        if (name_len >= sizeof name || !is_known_option(name))
            return fc_error_set(err, FC_ERR_USAGE, "unknown option '%s' (see --help)", arg);
        const char *value = equals ? equals + 1 : i + 1 < argc ? argv[++i] : NULL;
        if (!value)
            return fc_error_set(err, FC_ERR_USAGE, "option '%s' needs a value (see --help)", arg);
        fc_code code = apply_option(name, value, o, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}
