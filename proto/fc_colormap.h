/* fc_colormap.h — the colormaps of fc_settings.colormap as 256-entry tables
 * (fc_colormap_tables.c, generated from matplotlib by
 * gen_colormap_tables.py), their names, and the colour of a value. The
 * renderer uploads the tables; clients use the names and colours for their
 * options and legends. */
#ifndef FC_COLORMAP_H
#define FC_COLORMAP_H

#include <stdbool.h>

#include "fluidcast_types.h"

#define FC_COLORMAP_ENTRIES 256
#define FC_COLORMAP_COUNT (FC_COLORMAP_TURBO + 1)

/* The table of `map`: FC_COLORMAP_ENTRIES sRGB colours in [0, 1], entry i at
 * the position i / 255 of the range, as matplotlib samples its maps. */
const float (*fc_colormap_table(fc_colormap map))[3];

/* The map's name ("viridis", ...); "?" for a value outside the enum. */
const char *fc_colormap_name(fc_colormap map);

/* Every map's name, indexed by fc_colormap, then NULL (the colormap setting's choices). */
extern const char *const fc_colormap_names[FC_COLORMAP_COUNT + 1];

/* The map called `name` (as fc_colormap_name spells it), false for none. */
bool fc_colormap_parse(const char *name, fc_colormap *map);

/* The sRGB colour at position t of the range (clamped to [0, 1]), linearly
 * interpolated between the table's entries as the renderer's lookup is. */
void fc_colormap_srgb(fc_colormap map, float t, float rgb[3]);

/* The colour as linear RGB, interpolated between the entries' linear
 * colours: what the renderer tints the fluid with. */
void fc_colormap_linear(fc_colormap map, float t, float rgb[3]);

/* sRGB-encoded value in [0, 1] to linear light (IEC 61966-2-1). */
float fc_srgb_to_linear(float c);

#endif
