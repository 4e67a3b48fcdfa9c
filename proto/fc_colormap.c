/* fc_colormap.c — colormap names and lookups over the generated tables. */
#include "fc_colormap.h"

#include <math.h>
#include <string.h>

#include "fc_colormap_tables.h"

const char *const fc_colormap_names[FC_COLORMAP_COUNT + 1] = {
    [FC_COLORMAP_VIRIDIS] = "viridis", [FC_COLORMAP_PLASMA] = "plasma",   [FC_COLORMAP_INFERNO] = "inferno",
    [FC_COLORMAP_MAGMA] = "magma",     [FC_COLORMAP_CIVIDIS] = "cividis", [FC_COLORMAP_COOLWARM] = "coolwarm",
    [FC_COLORMAP_TURBO] = "turbo",       [FC_COLORMAP_COUNT] = NULL,
};

static bool is_map(fc_colormap map)
{
    return (unsigned)map < FC_COLORMAP_COUNT;
}

const float (*fc_colormap_table(fc_colormap map))[3]
{
    return fc_colormap_tables[is_map(map) ? map : FC_COLORMAP_VIRIDIS];
}

const char *fc_colormap_name(fc_colormap map)
{
    return is_map(map) ? fc_colormap_names[map] : "?";
}

bool fc_colormap_parse(const char *name, fc_colormap *map)
{
    for (int i = 0; i < FC_COLORMAP_COUNT; i++)
        if (strcmp(name, fc_colormap_names[i]) == 0) {
            *map = (fc_colormap)i;
            return true;
        }
    return false;
}

/* The entry below position t and the fraction of the way to the next. */
static int entry_at(float t, float *fraction)
{
    /* NaN compares false both ways and lands on the first entry. */
    float x = t > 0.0f ? (t < 1.0f ? t : 1.0f) : 0.0f;
    float pos = x * (float)(FC_COLORMAP_ENTRIES - 1);
    int i = (int)pos;
    if (i >= FC_COLORMAP_ENTRIES - 1)
        i = FC_COLORMAP_ENTRIES - 2;
    *fraction = pos - (float)i;
    return i;
}

void fc_colormap_srgb(fc_colormap map, float t, float rgb[3])
{
    const float(*table)[3] = fc_colormap_table(map);
    float f;
    int i = entry_at(t, &f);
    for (int c = 0; c < 3; c++)
        rgb[c] = table[i][c] + f * (table[i + 1][c] - table[i][c]);
}

float fc_srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

/* Interpolated between linear entries, as the renderer's table of linear
 * colours is sampled. */
void fc_colormap_linear(fc_colormap map, float t, float rgb[3])
{
    const float(*table)[3] = fc_colormap_table(map);
    float f;
    int i = entry_at(t, &f);
    for (int c = 0; c < 3; c++) {
        float a = fc_srgb_to_linear(table[i][c]), b = fc_srgb_to_linear(table[i + 1][c]);
        rgb[c] = a + f * (b - a);
    }
}
