/* view_module.c — fluidcast-view.so: `fluidcast view` behind view_module.h.
 * The only symbol it exports is the interface; SDL2 and libav come with it. */
#include "view_module.h"

#include "view.h"

__attribute__((visibility("default"))) extern const fc_view_module fc_view_module_v1;

const fc_view_module fc_view_module_v1 = {
    .abi = FC_VIEW_MODULE_ABI,
    .main = fc_view_main,
};
