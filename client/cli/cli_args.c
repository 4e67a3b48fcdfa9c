/* cli_args.c — see cli_args.h. */
#include "cli_args.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

fc_code fc_cli_parse_args(const fc_cli_command *command, int argc, char **argv, void *options, bool *help,
                          fc_error *err)
{
    *help = false;
    fc_option *rows = calloc(command->option_count ? command->option_count : 1, sizeof *rows);
    if (!rows)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the options of fluidcast %s", command->name);
    for (size_t i = 0; i < command->option_count; i++) {
        const fc_cli_option *option = &command->options[i];
        rows[i] = (fc_option){option->name, option->takes_value ? "VALUE" : NULL, option->set, NULL, NULL};
    }
    char program[64];
    snprintf(program, sizeof program, "fluidcast %s", command->name);
    const fc_option_table table = {program, rows, command->option_count, command->positional, command->more};
    fc_code code = fc_options_parse(&table, argc, argv, options, help, err);
    free(rows);
    return code;
}

fc_code fc_cli_take_global(int *argc, char **argv, const char *option,
                           fc_code (*apply)(const char *value, fc_error *err), fc_error *err)
{
    size_t option_len = strlen(option);
    int kept = 1;
    fc_code code = FC_OK;
    for (int i = 1; i < *argc; i++) {
        const char *arg = argv[i];
        if (code != FC_OK || !fc_option_matches(arg, option)) {
            argv[kept++] = argv[i];
            continue;
        }
        const char *value = arg[option_len] == '=' ? arg + option_len + 1 : i + 1 < *argc ? argv[++i] : NULL;
        code = value ? apply(value, err) : fc_error_set(err, FC_ERR_USAGE, "%s needs a value", option);
    }
    *argc = kept;
    argv[kept] = NULL;
    return code;
}
