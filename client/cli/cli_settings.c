/* cli_settings.c — see cli_settings.h. */
#include "cli_settings.h"

#include "fc_frame.h"

void fc_cli_default_settings(fc_settings *s)
{
    fc_settings_default(s);
    s->kernel = FC_KERNEL_ANISOTROPIC;
}
