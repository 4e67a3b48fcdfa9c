/* view_module.h — the interface of fluidcast-view.so (modules/view_module.c):
 * the whole of `fluidcast view` (client/viewer: SDL2's window, libavcodec's
 * decoders, the SpaceMouse), which view_command.c opens with fc_cli_module_open
 * (cli_module.h) for that command only, so no other command loads SDL2 or libav. */
#ifndef FC_VIEW_MODULE_H
#define FC_VIEW_MODULE_H

#include <stdint.h>

#define FC_VIEW_MODULE_FILE "fluidcast-view.so"
#define FC_VIEW_MODULE_SYMBOL "fc_view_module_v1"
/* Raised whenever the struct below changes. */
#define FC_VIEW_MODULE_ABI 1u

typedef struct fc_view_module {
    uint32_t abi;   /* FC_VIEW_MODULE_ABI: first, checked when the module is opened */
    /* fc_view_main (client/viewer/view.h): the arguments after "view"; returns the exit status. */
    int (*main)(int argc, char **argv);
} fc_view_module;

#endif
