/* cli_args.c — see cli_args.h. */
#include "cli_args.h"

#include <string.h>

#include "fc_error.h"

/* The option `arg` names, as "--name" or "--name=value" (then *inline_value
 * points at the value). NULL when unknown. */
static const fc_cli_option *find_option(const fc_cli_command *command, const char *arg, const char **inline_value)
{
    *inline_value = NULL;
    size_t name_len = strcspn(arg, "=");
    for (size_t i = 0; i < command->option_count; i++) {
        const fc_cli_option *option = &command->options[i];
        if (strlen(option->name) == name_len && strncmp(arg, option->name, name_len) == 0) {
            if (arg[name_len] == '=')
                *inline_value = arg + name_len + 1;
            return option;
        }
    }
    return NULL;
}

static fc_code take_positional(const fc_cli_command *command, const char *arg, void *options, fc_error *err)
{
    if (!command->positional)
        return fc_error_set(err, FC_ERR_USAGE, "unexpected argument \"%s\" (see fluidcast %s --help)", arg,
                            command->name);
    return command->positional(options, arg, err);
}

/* argv[*i] as a render setting's option, with its value. */
static fc_code take_setting(const fc_cli_command *command, int argc, char **argv, int *i, void *options,
                            fc_error *err)
{
    const char *value;
    const fc_setting_spec *spec = fc_cli_find_setting(argv[*i], &value);
    if (!spec)
        return fc_error_set(err, FC_ERR_USAGE, "unknown option %s (see fluidcast %s --help)", argv[*i],
                            command->name);
    if (!value) {
        if (*i + 1 >= argc)
            return fc_error_set(err, FC_ERR_USAGE, "%s needs a value", spec->option);
        value = argv[++*i];
    }
    return fc_cli_set_setting(command->settings(options), spec, value, err);
}

fc_code fc_cli_parse_args(const fc_cli_command *command, int argc, char **argv, void *options, bool *help,
                          fc_error *err)
{
    *help = false;
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            *help = true;
            return FC_OK;
        }
        fc_code code;
        if (arg[0] != '-' || arg[1] == '\0') {
            code = take_positional(command, arg, options, err);
        } else {
            const char *value;
            const fc_cli_option *option = find_option(command, arg, &value);
            if (!option && command->settings) {
                code = take_setting(command, argc, argv, &i, options, err);
                if (code != FC_OK)
                    return code;
                continue;
            }
            if (!option)
                return fc_error_set(err, FC_ERR_USAGE, "unknown option %s (see fluidcast %s --help)", arg,
                                    command->name);
            if (!option->takes_value && value)
                return fc_error_set(err, FC_ERR_USAGE, "%s takes no value", option->name);
            if (option->takes_value && !value) {
                if (i + 1 >= argc)
                    return fc_error_set(err, FC_ERR_USAGE, "%s needs a value", option->name);
                value = argv[++i];
            }
            code = option->set(options, option->name, value, err);
        }
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

fc_code fc_cli_take_global(int *argc, char **argv, const char *option,
                           fc_code (*apply)(const char *value, fc_error *err), fc_error *err)
{
    size_t option_len = strlen(option);
    int kept = 1;
    fc_code code = FC_OK;
    for (int i = 1; i < *argc; i++) {
        const char *arg = argv[i];
        if (code != FC_OK || strncmp(arg, option, option_len) != 0 ||
            (arg[option_len] != '\0' && arg[option_len] != '=')) {
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
