/* cli_settings.h — the render settings the command line chooses from the
 * particles when the user leaves them out. */
#ifndef FC_CLI_SETTINGS_H
#define FC_CLI_SETTINGS_H

#include <stdbool.h>

#include "fluidcast_types.h"

/* What fc_cli_complete_settings chose. */
typedef struct fc_cli_choices {
    bool radius;   /* the radius was estimated from the particle spacing */
    bool spray;    /* the spray threshold was set from the frame's densities */
} fc_cli_choices;

/* Completes the settings from a frame (the first of a sequence): a radius
 * <= 0 is estimated from the particle spacing (fc_frame_estimate_radius:
 * side by side on the splash frames and the demo scene, smaller radii made
 * ellipsoids no crisper, and jittered surfaces pebbly); unless the user
 * gave one, a frame with densities gets a spray threshold of half its median
 * density, so that single-particle droplets (an isolated SPH particle has
 * about a third of the rest density) are drawn as white spray instead of as
 * clear beads that hardly show. */
void fc_cli_complete_settings(fc_settings *s, const fc_frame *frame, bool threshold_given, fc_cli_choices *chosen);

#endif
