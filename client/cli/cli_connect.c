/* cli_connect.c — see cli_connect.h. */
#define _POSIX_C_SOURCE 200809L
#include "cli_connect.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "cli_token.h"
#include "fc_error.h"
#include "fc_options.h"

static const char TIMEOUT_OPTION[] = "--connect-timeout";
static const char TIMEOUT_VARIABLE[] = "FLUIDCAST_CONNECT_TIMEOUT";
#define TIMEOUT_MAX_S 3600.0

/* Seconds in (0, TIMEOUT_MAX_S] as milliseconds (at least 1); 0 when `text` is none. */
static uint32_t timeout_ms(const char *text)
{
    char *end = NULL;
    errno = 0;
    double seconds = strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0' || !(seconds > 0.0 && seconds <= TIMEOUT_MAX_S))
        return 0;
    uint32_t ms = (uint32_t)(seconds * 1000.0 + 0.5);
    return ms > 0 ? ms : 1;
}

static fc_code publish_timeout(const char *value, fc_error *err)
{
    if (timeout_ms(value) == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s %s: not a number of seconds in (0, %.0f]", TIMEOUT_OPTION,
                            value, TIMEOUT_MAX_S);
    if (setenv(TIMEOUT_VARIABLE, value, 1) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot set %s: %s", TIMEOUT_VARIABLE, strerror(errno));
    return FC_OK;
}

fc_code fc_cli_connect_timeout_take(int *argc, char **argv, fc_error *err)
{
    return fc_cli_take_global(argc, argv, TIMEOUT_OPTION, publish_timeout, err);
}

/* The TLS options, each once: flag, value, environment variable, help. */
typedef struct tls_option {
    const char *flag;
    const char *value;      /* NULL: a switch */
    const char *variable;
    const char *help;
} tls_option;

enum { TLS_ON, TLS_CA, TLS_CERT, TLS_KEY, TLS_OPTIONS };
static const tls_option tls_options[TLS_OPTIONS] = {
    [TLS_ON] = {"--tls", NULL, "FLUIDCAST_TLS",
                "connect with TLS (as a tls:// address does); the server's certificate must name the host"},
    [TLS_CA] = {"--tls-ca", "FILE", "FLUIDCAST_TLS_CA",
                "the CAs (PEM) the server's certificate must chain to; default: the system's"},
    [TLS_CERT] = {"--tls-cert", "FILE", "FLUIDCAST_TLS_CERT", "a client certificate (PEM), for mutual TLS"},
    [TLS_KEY] = {"--tls-key", "FILE", "FLUIDCAST_TLS_KEY", "its private key (PEM); default: in --tls-cert's file"},
};

static fc_code publish(const tls_option *option, const char *value, fc_error *err)
{
    if (setenv(option->variable, value, 1) != 0)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot set %s: %s", option->variable, strerror(errno));
    return FC_OK;
}

static fc_code publish_ca(const char *value, fc_error *err)
{
    return publish(&tls_options[TLS_CA], value, err);
}

static fc_code publish_cert(const char *value, fc_error *err)
{
    return publish(&tls_options[TLS_CERT], value, err);
}

static fc_code publish_key(const char *value, fc_error *err)
{
    return publish(&tls_options[TLS_KEY], value, err);
}

/* Removes every "--tls" switch from argv; FC_OK, or the error of publishing it. */
static fc_code take_switch(int *argc, char **argv, const tls_option *option, fc_error *err)
{
    int kept = 1;
    bool seen = false;
    for (int i = 1; i < *argc; i++) {
        if (strcmp(argv[i], option->flag) == 0)
            seen = true;
        else
            argv[kept++] = argv[i];
    }
    *argc = kept;
    argv[kept] = NULL;
    return seen ? publish(option, "1", err) : FC_OK;
}

fc_code fc_cli_tls_take(int *argc, char **argv, fc_error *err)
{
    fc_code (*const publishers[TLS_OPTIONS])(const char *, fc_error *) = {
        [TLS_CA] = publish_ca, [TLS_CERT] = publish_cert, [TLS_KEY] = publish_key};
    fc_code code = take_switch(argc, argv, &tls_options[TLS_ON], err);
    for (int i = TLS_CA; code == FC_OK && i < TLS_OPTIONS; i++)
        code = fc_cli_take_global(argc, argv, tls_options[i].flag, publishers[i], err);
    return code;
}

void fc_cli_tls_print_help(FILE *to)
{
    for (int i = 0; i < TLS_OPTIONS; i++) {
        char help[256];
        snprintf(help, sizeof help, "%s (or %s)", tls_options[i].help, tls_options[i].variable);
        const fc_option row = {tls_options[i].flag, tls_options[i].value, NULL, help, NULL};
        fc_options_print_option(to, &row);   /* wrapped like every other option's help */
    }
}

static const char *tls_setting(int which)
{
    const char *value = getenv(tls_options[which].variable);
    return value && value[0] ? value : NULL;
}

fc_connect_options fc_cli_connect_options(const char *client_name)
{
    const char *timeout = getenv(TIMEOUT_VARIABLE);
    const char *tls = tls_setting(TLS_ON);
    return (fc_connect_options){.client_name = client_name,
                                .token = fc_cli_token(),
                                .connect_timeout_ms = timeout ? timeout_ms(timeout) : 0,
                                .tls = tls && strcmp(tls, "0") != 0,
                                .tls_ca_file = tls_setting(TLS_CA),
                                .tls_cert_file = tls_setting(TLS_CERT),
                                .tls_key_file = tls_setting(TLS_KEY)};
}

fc_code fc_cli_connect(const char *server, const char *session, const fc_connect_options *options,
                       fc_client **out, fc_error *err)
{
    fc_code code = fc_client_connect_session(server, session, options, out, err);
    if (code == FC_OK && server && strncmp(server, "srv:", 4) == 0) {
        if (session)
            fprintf(stderr, "fluidcast: %s -> %s (session %s)\n", server, fc_client_address(*out), session);
        else
            fprintf(stderr, "fluidcast: %s -> %s\n", server, fc_client_address(*out));
    }
    return code;
}
