/* cli_args.h — a subcommand's arguments through the shared option parser
 * (proto/fc_options.h): "--name value", "--name=value", flags without a value,
 * positional arguments and --help; and the options every subcommand takes. */
#ifndef FC_CLI_ARGS_H
#define FC_CLI_ARGS_H

#include <stdbool.h>
#include <stddef.h>

#include "fc_options.h"
#include "fluidcast_types.h"

/* Applies one option to the subcommand's options struct; value is NULL for a flag. */
typedef fc_option_setter fc_cli_setter;

/* A subcommand's option: the three fields of an fc_option the subcommands
 * use (their help texts are written by hand), handed to the shared parser as
 * fc_option rows with "VALUE" as the value's name. */
typedef struct fc_cli_option {
    const char *name;          /* "--session" */
    bool takes_value;
    fc_cli_setter set;
} fc_cli_option;

typedef struct fc_cli_command {
    const char *name;                      /* "stream": errors say "see fluidcast stream --help" */
    const fc_cli_option *options;
    size_t option_count;
    /* Takes one positional argument; NULL: positional arguments are refused. */
    fc_code (*positional)(void *options, const char *arg, fc_error *err);
    /* Options beyond the command's own (fc_option_table.more): the render
     * settings' (fc_cli_take_setting) for the commands that render; NULL: none. */
    fc_code (*more)(void *options, int argc, char **argv, int *i, bool *known, fc_error *err);
} fc_cli_command;

/* Parses argv (the arguments after the subcommand) into `options` with
 * fc_options_parse. Stops at --help/-h with *help true. FC_ERR_USAGE naming the
 * offending argument. */
fc_code fc_cli_parse_args(const fc_cli_command *command, int argc, char **argv, void *options, bool *help,
                          fc_error *err);

/* Removes every "OPTION VALUE" / "OPTION=VALUE" from argv[1..] (updating *argc),
 * wherever it stands, and hands each value to `apply`: the options every
 * subcommand takes (--token-file, --connect-timeout). FC_ERR_USAGE for a
 * missing value; else the first error of `apply`. */
fc_code fc_cli_take_global(int *argc, char **argv, const char *option,
                           fc_code (*apply)(const char *value, fc_error *err), fc_error *err);

#endif
