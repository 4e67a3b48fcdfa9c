/* cli_settings.h — the render settings the command line starts from. */
#ifndef FC_CLI_SETTINGS_H
#define FC_CLI_SETTINGS_H

#include "fluidcast_types.h"

/* The protocol's defaults (fc_settings_default), except that particles are
 * anisotropic ellipsoids: people render with the CLI to look at the picture,
 * and side by side on real solver output the ellipsoids close sheets and
 * smooth surfaces that spheres leave pitted (README, gallery). The protocol
 * keeps spheres as its default, the exact shape its analytic tests and
 * existing clients rely on. */
void fc_cli_default_settings(fc_settings *s);

#endif
