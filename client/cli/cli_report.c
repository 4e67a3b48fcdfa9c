/* cli_report.c — see cli_report.h. */
#include "cli_report.h"

#include <stdarg.h>

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
}

int fc_cli_exit_for_client_error(fc_code code)
{
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
