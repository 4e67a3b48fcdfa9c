/* cli_report.h — the fluidcast command's exit codes and how failures are told:
 * one line on stderr prefixed "fluidcast: ", and a distinct exit status per
 * kind of failure so scripts can tell them apart (curl-style). */
#ifndef FC_CLI_REPORT_H
#define FC_CLI_REPORT_H

#include <stdio.h>

#include "fluidcast_types.h"

enum fc_cli_exit {
    FC_EXIT_OK = 0,
    FC_EXIT_USAGE = 2,        /* bad command line */
    FC_EXIT_INPUT = 3,        /* input file unreadable or malformed */
    FC_EXIT_CONNECT = 4,      /* the server cannot be reached */
    FC_EXIT_SERVER = 5,       /* the server answered with an error */
    FC_EXIT_OUTPUT = 6,       /* the output file cannot be written */
    FC_EXIT_CONNECTION = 7,   /* protocol or connection failure after connecting */
    /* TLS failures, one status per cause (the table in cli_report.c says which fc_code) */
    FC_EXIT_TLS_UNKNOWN_CA = 8,
    FC_EXIT_TLS_NAME_MISMATCH = 9,
    FC_EXIT_TLS_EXPIRED = 10,
    FC_EXIT_TLS_REQUIRED = 11,
    FC_EXIT_TLS_PLAINTEXT_PEER = 12,
    FC_EXIT_TLS_CLIENT_CERT = 13,
    FC_EXIT_TLS = 14
};

/* Prints the table of exit statuses, for the help texts. */
void fc_cli_print_exit_codes(FILE *to);

/* The exit status for a failure of a libfluidcast call. */
int fc_cli_exit_for_client_error(fc_code code);

/* Prints "fluidcast: " + the formatted message on stderr; returns exit_code. */
int fc_cli_fail(int exit_code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif
