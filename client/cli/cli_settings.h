/* cli_settings.h — the render settings the command line chooses from the
 * particles when the user leaves them out. */
#ifndef FC_CLI_SETTINGS_H
#define FC_CLI_SETTINGS_H

#include <stdbool.h>

#include "fluidcast_types.h"

/* What fc_cli_complete_settings chose. */
typedef struct fc_cli_choices {
    bool radius;   /* the radius was estimated from the particle spacing */
    bool per_particle_radius;   /* radius left at 0: the frame's own radii are used (median below) */
    float median_radius;        /* the frame's median radius, when per_particle_radius */
    bool color_range;   /* the colour range was set from the frame's attribute */
} fc_cli_choices;

/* Completes the settings from a frame (the first of a sequence): a radius
 * <= 0 stays 0 when the frame has per-particle radii (the server splats each
 * particle at its own, PROTOCOL.md 5), and is otherwise estimated from the
 * particle spacing (fc_frame_estimate_radius:
 * side by side on the splash frames and the demo scene, smaller radii made
 * ellipsoids no crisper, and jittered surfaces pebbly). No density
 * threshold is chosen: spray is classified by neighbour count on the server
 * (spray_neighbours), and a threshold from the densities (it was half the
 * median) turned a thin crown or sheet, whose particles a solver gives low
 * densities, into dust (bench/LOOK.md). */
void fc_cli_complete_settings(fc_settings *s, const fc_frame *frame, fc_cli_choices *chosen);

/* Unless the user gave a range, a frame coloured by an attribute it has gets
 * the 2nd to 98th percentile of that attribute (over an evenly spread sample
 * of at most 65536 particles) as its colour range, so that a few outliers do
 * not squeeze every other particle into one colour; a constant attribute v
 * gets [v, v + 1]. Sets chosen->color_range when it did. */
void fc_cli_complete_color_range(fc_settings *s, const fc_frame *frame, bool range_given, fc_cli_choices *chosen);

/* Prints the colour range fc_cli_complete_color_range chose, as a --range to paste. */
void fc_cli_print_color_range(const fc_settings *s);

/* The radius line of snapshot and render: the radius, and how it was chosen. */
void fc_cli_print_radius(const fc_settings *s, const fc_cli_choices *chosen, const char *estimated_from);

#endif
