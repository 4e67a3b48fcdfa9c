/* view_command.c — see view_command.h. */
#include "view_command.h"

#include "cli_module.h"
#include "cli_report.h"
#include "view_module.h"

int fc_view_command(int argc, char **argv)
{
    fc_cli_module module;
    fc_error err;
    if (fc_cli_module_open(FC_VIEW_MODULE_FILE, FC_VIEW_MODULE_SYMBOL, FC_VIEW_MODULE_ABI, "fluidcast view",
                           &module, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    const fc_view_module *view = module.api;
    int status = view->main(argc, argv);
    fc_cli_module_close(&module);
    return status;
}
