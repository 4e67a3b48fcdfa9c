/* options.h — fluidcastd's command line. */
#ifndef FC_DAEMON_OPTIONS_H
#define FC_DAEMON_OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

#include "fc_host_port.h"
#include "gl/egl_context.h"
#include "log.h"
#include "wire.h"

typedef struct fc_daemon_options {
    char listen_host[FC_HOST_MAX];   /* name or address; brackets of "[v6]:port" removed */
    char listen_port[FC_PORT_MAX];   /* decimal, "0" = any free port */
    bool listen_given;         /* --listen was given: with --unix, TCP is served only then */
    const char *unix_path;     /* --unix: NULL for none; points into argv */
    fc_gpu_choice gpu;
    fc_log_level log_level;
    const char *shader_dir;    /* NULL: shaders built into the binary; points into argv */
    const char *port_file;     /* NULL: none; points into argv */
    fc_limits limits;
    uint32_t chunk_timeout_ms; /* how long a multi-rank frame may wait for its chunks */
    uint32_t refresh_ms;       /* quiet time before a lossless refresh of a lossy stream image; 0 = never */
    uint32_t encoders;         /* encoder threads; 0 = min(4, cores) */
    uint32_t png_compression;  /* PNG's zlib level 0..9 (proto/image/image_encoder.h) */
    uint32_t max_sessions;     /* named sessions at once */
    uint32_t max_connections;  /* client connections at once; more are refused with LIMIT */
    uint32_t idle_timeout_ms;  /* close a connection with no complete message for this long; 0 = never */
    uint32_t read_timeout_ms;  /* a started message must be complete within this; 0 = never */
    uint64_t max_session_memory;   /* bytes one connection (with the named session it produces) may hold */
    char metrics_host[FC_HOST_MAX];  /* --metrics-listen: "" = no metrics endpoint */
    char metrics_port[FC_PORT_MAX];
    char web_host[FC_HOST_MAX];      /* --web-listen: "" = no web viewer */
    char web_port[FC_PORT_MAX];
    const char *token_file;    /* --token-file: NULL for none (then FLUIDCAST_TOKEN); points into argv */
    const char *tls_cert;      /* --tls-cert: NULL = TCP in clear; points into argv */
    const char *tls_key;       /* --tls-key: the certificate's private key */
    const char *tls_client_ca; /* --tls-client-ca: mutual TLS, clients need a certificate from these CAs */
    uint32_t tls_handshake_timeout_ms;  /* a TLS handshake not complete within this is dropped */
    bool metrics_tls;          /* --metrics-tls: the metrics endpoint over HTTPS with --tls-cert/--tls-key */
    bool help;                 /* -h/--help: print usage and exit */
} fc_daemon_options;

/* The defaults of options.c's table, where each option's flag, default and
 * help are written once; an error only for a default its setter refuses. */
fc_code fc_daemon_options_default(fc_daemon_options *o, fc_error *err);

/* Parses argv (argv[0] the program) over the defaults already in *o with
 * fc_options_parse: "--name value" and "--name=value"; FC_ERR_USAGE naming
 * the offending argument. */
fc_code fc_daemon_options_parse(int argc, char **argv, fc_daemon_options *o, fc_error *err);

/* FC_ERR_USAGE when the TLS options do not go together: --tls-cert and
 * --tls-key are given both or neither, --tls-client-ca only with them. */
fc_code fc_daemon_options_check_tls(const fc_daemon_options *o, fc_error *err);

/* TCP is served unless only --unix was given. */
bool fc_daemon_options_serve_tcp(const fc_daemon_options *o);

/* Parses --listen's address (fc_host_port.h; port 0 = any free port, none = FC_DEFAULT_PORT). */
fc_code fc_daemon_options_parse_listen(const char *text, fc_daemon_options *o, fc_error *err);
/* Parses --metrics-listen's "HOST:PORT", "[IPV6]:PORT" or "PORT" (then on
 * FC_DEFAULT_HOST: the metrics are for the operator, not the world). */
fc_code fc_daemon_options_parse_metrics_listen(const char *text, fc_daemon_options *o, fc_error *err);

/* Parses --web-listen's address, by the rules of --metrics-listen. */
fc_code fc_daemon_options_parse_web_listen(const char *text, fc_daemon_options *o, fc_error *err);

void fc_daemon_options_print_help(FILE *out, const char *program);

#endif
