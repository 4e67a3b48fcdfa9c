/* cli_report.c — see cli_report.h. */
#include "cli_report.h"

#include <stdarg.h>

/* A library code with an exit status of its own, and what the status means. */
typedef struct code_exit {
    fc_code code;
    int exit_status;
    const char *meaning;
} code_exit;

static const code_exit tls_exits[] = {
    {FC_ERR_TLS_UNKNOWN_CA, FC_EXIT_TLS_UNKNOWN_CA, "TLS: the server's certificate is not from a trusted CA"},
    {FC_ERR_TLS_NAME_MISMATCH, FC_EXIT_TLS_NAME_MISMATCH, "TLS: the server's certificate does not name the host"},
    {FC_ERR_TLS_EXPIRED, FC_EXIT_TLS_EXPIRED, "TLS: the server's certificate has expired (or is not valid yet)"},
    {FC_ERR_TLS_REQUIRED, FC_EXIT_TLS_REQUIRED, "the server wants TLS (tls:// or --tls)"},
    {FC_ERR_TLS_PLAINTEXT_PEER, FC_EXIT_TLS_PLAINTEXT_PEER, "TLS asked for, but the server speaks in clear"},
    {FC_ERR_TLS_CLIENT_CERT, FC_EXIT_TLS_CLIENT_CERT, "TLS: the server wants a client certificate it trusts"},
    {FC_ERR_TLS, FC_EXIT_TLS, "another TLS failure (certificate files, handshake)"},
};
enum { TLS_EXITS = sizeof tls_exits / sizeof tls_exits[0] };

void fc_cli_print_exit_codes(FILE *to)
{
    fputs("exit status:\n"
          "  0  success\n"
          "  2  usage error (bad option or value)\n"
          "  3  the input file is unreadable or malformed\n"
          "  4  the server cannot be reached\n"
          "  5  the server answered with an error\n"
          "  6  the output file cannot be written\n"
          "  7  protocol or connection failure after connecting\n",
          to);
    for (size_t i = 0; i < TLS_EXITS; i++)
        fprintf(to, "  %-2d %s\n", tls_exits[i].exit_status, tls_exits[i].meaning);
}

int fc_cli_exit_for_client_error(fc_code code)
{
    for (size_t i = 0; i < TLS_EXITS; i++)
        if (tls_exits[i].code == code)
            return tls_exits[i].exit_status;
    if (code >= 1 && code <= 99)   /* wire codes: the server's verdict */
        return FC_EXIT_SERVER;
    if (code == FC_ERR_CONNECT)
        return FC_EXIT_CONNECT;
    if (code == FC_ERR_USAGE)      /* a malformed --server address */
        return FC_EXIT_USAGE;
    return FC_EXIT_CONNECTION;
}

int fc_cli_fail(int exit_code, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    fputs("fluidcast: ", stderr);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
    return exit_code;
}
