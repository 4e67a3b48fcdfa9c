/* cli_args.h — table-driven parsing of a subcommand's arguments: "--name value",
 * "--name=value", flags without a value, positional arguments and --help. */
#ifndef FC_CLI_ARGS_H
#define FC_CLI_ARGS_H

#include <stdbool.h>
#include <stddef.h>

#include "cli_setting_options.h"
#include "fluidcast_types.h"

/* Applies one option to the subcommand's options struct; value is NULL for a flag. */
typedef fc_code (*fc_cli_setter)(void *options, const char *name, const char *value, fc_error *err);

typedef struct fc_cli_option {
    const char *name;          /* "--session" */
    bool takes_value;
    fc_cli_setter set;
} fc_cli_option;

typedef struct fc_cli_command {
    const char *name;                      /* "stream", for messages */
    const fc_cli_option *options;
    size_t option_count;
    /* Takes one positional argument; NULL: positional arguments are refused. */
    fc_code (*positional)(void *options, const char *arg, fc_error *err);
    /* The command's render settings, whose options (cli_setting_options.h, from
     * the settings table) it takes besides its own; NULL: it takes none. */
    fc_cli_settings *(*settings)(void *options);
} fc_cli_command;

/* Parses argv (the arguments after the subcommand) into `options`. Stops at
 * --help/-h with *help true. FC_ERR_USAGE naming the offending argument. */
fc_code fc_cli_parse_args(const fc_cli_command *command, int argc, char **argv, void *options, bool *help,
                          fc_error *err);

/* Removes every "OPTION VALUE" / "OPTION=VALUE" from argv[1..] (updating *argc),
 * wherever it stands, and hands each value to `apply`: the options every
 * subcommand takes (--token-file, --connect-timeout). FC_ERR_USAGE for a
 * missing value; else the first error of `apply`. */
fc_code fc_cli_take_global(int *argc, char **argv, const char *option,
                           fc_code (*apply)(const char *value, fc_error *err), fc_error *err);

#endif
