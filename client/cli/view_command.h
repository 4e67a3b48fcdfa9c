/* view_command.h — `fluidcast view`, run from its module (view_module.h). */
#ifndef FC_VIEW_COMMAND_H
#define FC_VIEW_COMMAND_H

/* Opens fluidcast-view.so and runs the viewer with the arguments after
 * "view"; its exit status. Exit 2 (as when SDL cannot start) with the module
 * and the loader's reason when the module cannot be loaded. */
int fc_view_command(int argc, char **argv);

#endif
