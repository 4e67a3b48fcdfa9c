/* fc_settings.c — the render settings' table (fc_settings.h): one entry per
 * field of fc_settings, and the defaults and validation made from it. */
#include "fc_settings.h"

#include <float.h>
#include <stdbool.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fc_colormap.h"
#include "fc_frame.h"

/* Every value of every field is 4 bytes, so a field is `count` words. */
_Static_assert(sizeof(float) == 4 && sizeof(uint32_t) == 4, "settings values are 4-byte words");
_Static_assert(sizeof(fc_smoothing) == 4 && sizeof(fc_kernel) == 4 && sizeof(fc_color_by) == 4 &&
                   sizeof(fc_colormap) == 4 && sizeof(fc_jpeg_subsampling) == 4 &&
                   sizeof(fc_surface_mode) == 4 && sizeof(fc_surface_kernel) == 4,
               "CHOICE fields that are enums are stored in 4 bytes, like a uint32_t");

static const char *const smoothing_names[] = {"none", "curvature", "bilateral", "binomial", "narrow", NULL};
static const char *const kernel_names[] = {"sphere", "anisotropic", NULL};
static const char *const switch_names[] = {"off", "on", NULL};
static const char *const color_by_names[] = {"none", "speed", "density", NULL};
static const char *const subsampling_names[] = {"444", "420", NULL};
static const char *const surface_names[] = {"screen", "mesh", NULL};
static const char *const surface_kernel_names[] = {"metaball", "sph", "anisotropic", NULL};

/* The enums' last values, so that a new enum value without a name fails to compile. */
_Static_assert(sizeof smoothing_names / sizeof *smoothing_names == FC_SMOOTHING_NARROW + 2, "smoothing names");
_Static_assert(sizeof kernel_names / sizeof *kernel_names == FC_KERNEL_ANISOTROPIC + 2, "kernel names");
_Static_assert(sizeof color_by_names / sizeof *color_by_names == FC_COLOR_BY_DENSITY + 2, "color_by names");
_Static_assert(sizeof subsampling_names / sizeof *subsampling_names == FC_JPEG_SUBSAMPLING_YUV420 + 2,
               "jpeg_subsampling names");
_Static_assert(sizeof surface_names / sizeof *surface_names == FC_SURFACE_MODE_MESH + 2, "surface names");
_Static_assert(sizeof surface_kernel_names / sizeof *surface_kernel_names == FC_SURFACE_KERNEL_ANISOTROPIC + 2,
               "surface_kernel names");

/* The entry's first fields: key, name, type, count, offset (the name is the field's). */
#define FIELD(k, field, t, n) .key = (k), .name = #field, .type = (t), .count = (n), \
                              .offset = offsetof(fc_settings, field)

static const fc_setting_spec table[] = {
    {FIELD(1, radius, FC_SETTING_FLOAT, 1), .initial = {0.0f}, .min = 0.0, .max = FC_FRAME_MAX_RADIUS,
     .flags = FC_SETTING_CLI_POSITIVE | FC_SETTING_FROM_FRAME, .group = FC_GROUP_SURFACE, .option = "--radius", .metavar = "R",
     .help = "particle sphere radius in world units, for every particle. Without it each particle keeps the "
             "radius its file gives, or else the radius is estimated from the particle spacing (0.9 x the "
             "median nearest-neighbour distance); the radius used is printed"},
    {FIELD(2, smoothing, FC_SETTING_CHOICE, 1), .initial = {FC_SMOOTHING_NARROW}, .choices = smoothing_names,
     .group = FC_GROUP_SURFACE, .option = "--smoothing",
     .help = "depth smoothing: narrow-range filter (Truong & Yuksel 2018), curvature flow (van der Laan et al. "
             "2009), bilateral, binomial with silhouette map, or none"},
    {FIELD(3, iterations, FC_SETTING_UINT, 1), .initial = {4}, .min = 0, .max = 1000,
     .flags = FC_SETTING_PER_SMOOTHING, .group = FC_GROUP_SURFACE, .option = "--iterations", .metavar = "N",
     .help = "curvature-flow steps or filter passes"},
    {FIELD(4, fluid_color, FC_SETTING_FLOAT, 3), .initial = {0.02f, 0.15f, 0.28f}, .min = 0, .max = 1,
     .separator = ',', .group = FC_GROUP_SHADING, .option = "--color", .metavar = "R,G,B",
     .help = "linear colour of a thick layer"},
    {FIELD(5, absorption, FC_SETTING_FLOAT, 3), .initial = {0.02f, 0.007f, 0.0035f}, .min = 0, .max = 1e6,
     .separator = ',', .group = FC_GROUP_SHADING, .option = "--absorption", .metavar = "R,G,B",
     .help = "Beer-Lambert absorption per particle radius of thickness, per channel"},
    {FIELD(6, ior, FC_SETTING_FLOAT, 1), .initial = {1.33f}, .min = 1, .max = 3, .group = FC_GROUP_SHADING,
     .option = "--ior", .metavar = "N", .help = "index of refraction"},
    {FIELD(7, filter_radius, FC_SETTING_UINT, 1), .initial = {0}, .min = 0, .max = 64, .group = FC_GROUP_SURFACE,
     .option = "--filter-radius", .metavar = "PX",
     .help = "kernel half-width of the bilateral, binomial and narrow-range filters in pixels; 0 = from the "
             "particle size"},
    {FIELD(8, smooth_scale, FC_SETTING_SCALE, 1), .initial = {1.0f}, .group = FC_GROUP_SURFACE,
     .option = "--smooth-scale", .metavar = "S", .help = "resolution of the smoothing"},
    {FIELD(9, refraction, FC_SETTING_FLOAT, 1), .initial = {0.25f}, .min = 0, .max = 1000,
     .group = FC_GROUP_SHADING, .option = "--refraction", .metavar = "G",
     .help = "background offset per pixel of projected thickness"},
    {FIELD(10, specular, FC_SETTING_FLOAT, 1), .initial = {1.5f}, .min = 0, .max = 10, .group = FC_GROUP_SHADING,
     .option = "--specular", .metavar = "S", .help = "specular intensity"},
    {FIELD(11, shininess, FC_SETTING_FLOAT, 1), .initial = {400.0f}, .min = 1, .max = 10000,
     .group = FC_GROUP_SHADING, .option = "--shininess", .metavar = "E", .help = "specular exponent"},
    {FIELD(12, thickness_scale, FC_SETTING_SCALE, 1), .initial = {0.25f}, .group = FC_GROUP_SHADING,
     .option = "--thickness-scale", .metavar = "S", .help = "resolution of the thickness pass"},
    {FIELD(13, thickness_blur, FC_SETTING_UINT, 1), .initial = {2}, .min = 0, .max = 32,
     .group = FC_GROUP_SHADING, .option = "--thickness-blur", .metavar = "PX",
     .help = "blur radius of the thickness in pixels"},
    {FIELD(14, noise, FC_SETTING_FLOAT, 1), .initial = {0.0f}, .min = 0, .max = 10, .group = FC_GROUP_SURFACE,
     .option = "--noise", .metavar = "AMPLITUDE", .help = "surface noise; 0 = off"},
    {FIELD(15, foam, FC_SETTING_FLOAT, 1), .initial = {0.0f}, .min = 0, .max = 10, .group = FC_GROUP_SURFACE,
     .option = "--foam", .metavar = "INTENSITY", .help = "foam and spray; 0 = off"},
    {FIELD(16, foam_tau, FC_SETTING_FLOAT, 1), .initial = {0.5f}, .min = 0, .max = FLT_MAX,
     .flags = FC_SETTING_MIN_OPEN, .group = FC_GROUP_SURFACE, .option = "--foam-tau", .metavar = "V",
     .help = "velocity change per frame that raises foam"},
    /* A decay of 1 would never let a raised amplitude fall back. */
    {FIELD(17, foam_decay, FC_SETTING_FLOAT, 1), .initial = {0.85f}, .min = 0, .max = 1,
     .flags = FC_SETTING_MAX_OPEN, .group = FC_GROUP_SURFACE, .option = "--foam-decay", .metavar = "F",
     .help = "per-frame decay of raised foam"},
    {FIELD(18, density_threshold, FC_SETTING_FLOAT, 1), .initial = {0.0f}, .min = 0, .max = FLT_MAX,
     .flags = FC_SETTING_FROM_FRAME, .group = FC_GROUP_SURFACE, .option = "--density-threshold", .metavar = "D",
     .help = "particles with density below D are drawn as white spray; 0 = off. Default: half the frame's "
             "median density when the file has densities (printed), else off"},
    {FIELD(19, kernel, FC_SETTING_CHOICE, 1), .initial = {FC_KERNEL_SPHERE}, .choices = kernel_names,
     .group = FC_GROUP_SURFACE, .option = "--kernel",
     .help = "particle shape: spheres, or ellipsoids stretched along each particle's neighbours (Yu & Turk "
             "2013: flat sheets, long jets)"},
    {FIELD(20, shadow, FC_SETTING_CHOICE, 1), .initial = {1}, .choices = switch_names, .group = FC_GROUP_SHADING,
     .option = "--shadow", .help = "the fluid's soft shadow on the built-in floor"},
    {FIELD(21, exposure, FC_SETTING_FLOAT, 1), .initial = {0.0f}, .min = -16, .max = 16,
     .group = FC_GROUP_SHADING, .option = "--exposure", .metavar = "EV",
     .help = "stops of exposure before the filmic tone map"},
    {FIELD(22, color_by, FC_SETTING_CHOICE, 1), .initial = {FC_COLOR_BY_NONE}, .choices = color_by_names,
     .group = FC_GROUP_COLORING, .option = "--color-by",
     .help = "tint the fluid by each particle's speed (needs velocities) or density (needs densities): the "
             "colours are splatted and blurred with the thickness and thick fluid shows them; a frame without "
             "the attribute is an error"},
    {FIELD(23, colormap, FC_SETTING_CHOICE, 1), .initial = {FC_COLORMAP_VIRIDIS}, .choices = fc_colormap_names,
     .group = FC_GROUP_COLORING, .option = "--colormap", .help = "the colours the attribute's range runs through"},
    {FIELD(24, color_range, FC_SETTING_FLOAT, 2), .initial = {0.0f, 1.0f}, .min = -FLT_MAX, .max = FLT_MAX,
     .flags = FC_SETTING_RANGE | FC_SETTING_FROM_FRAME, .separator = ':', .group = FC_GROUP_COLORING,
     .option = "--range", .metavar = "MIN:MAX",
     .help = "attribute values at the map's ends, MIN < MAX; values outside take the end colours. Default: "
             "the first frame's 2nd to 98th percentile, printed, so that later runs can fix it and compare"},
    /* Keys 25-31 are reserved (PROTOCOL.md 7.5). */
    {FIELD(32, jpeg_subsampling, FC_SETTING_CHOICE, 1), .initial = {FC_JPEG_SUBSAMPLING_YUV444},
     .choices = subsampling_names, .group = FC_GROUP_IMAGE, .option = "--jpeg-subsampling",
     .help = "JPEG chroma: 444 keeps every pixel's colour, 420 shares one among 2x2 pixels (smaller files, a "
             "faster encode; .jpg/.jpeg only)"},
    /* Keys 33-39 are reserved (PROTOCOL.md 7.5). 2: the particles of a jet in a row keep 2 (its
     * ends) to 4 neighbours within 2.2 spacings, a lone droplet none and a pair of droplets one. */
    {FIELD(40, spray_neighbours, FC_SETTING_UINT, 1), .initial = {2}, .min = 0, .max = 64,
     .group = FC_GROUP_SURFACE, .option = "--spray-neighbours", .metavar = "N",
     .help = "particles with fewer than N others within 2.2 particle spacings are spray, drawn as small clear "
             "droplets of varied size instead of surface (Ihmsen et al. 2012); 0 = off"},
    /* Keys 41-44 are reserved (PROTOCOL.md 7.5). */
    {FIELD(45, surface, FC_SETTING_CHOICE, 1), .initial = {FC_SURFACE_MODE_SCREEN}, .choices = surface_names,
     .group = FC_GROUP_SURFACE, .option = "--surface",
     .help = "the fluid's surface: splatted and smoothed in screen space, or a mesh extracted from the "
             "particles' field (marching cubes on the GPU) and drawn with the same shading"},
    {FIELD(46, surface_cell, FC_SETTING_FLOAT, 1), .initial = {1.0f}, .min = 0.25, .max = 4,
     .flags = FC_SETTING_MIN_OPEN, .group = FC_GROUP_SURFACE, .option = "--surface-cell", .metavar = "C",
     .help = "the surface mesh's grid cell edge in particle radii (smaller: finer and slower)"},
    {FIELD(47, surface_kernel, FC_SETTING_CHOICE, 1), .initial = {FC_SURFACE_KERNEL_METABALL},
     .choices = surface_kernel_names, .group = FC_GROUP_SURFACE, .option = "--surface-kernel",
     .help = "the field the surface mesh follows: metaballs (Janisz), the cubic SPH kernel, or metaballs "
             "stretched along the anisotropic ellipsoids"},
    {FIELD(48, surface_smoothing, FC_SETTING_UINT, 1), .initial = {4}, .min = 0, .max = 100,
     .group = FC_GROUP_SURFACE, .option = "--surface-smoothing", .metavar = "N",
     .help = "Taubin smoothing steps of the surface mesh (volume kept); 0 = off"},
    {FIELD(57, contact_shadow, FC_SETTING_FLOAT, 1), .initial = {0.45f}, .min = 0, .max = 1,
     .group = FC_GROUP_SHADING, .option = "--contact-shadow", .metavar = "S",
     .help = "how much the water darkens where it meets the built-in floor (within 2.5 particle radii), so its "
             "foot shows on a floor of its own grey; 0 = off"},
    {FIELD(58, depth_dimming, FC_SETTING_FLOAT, 1), .initial = {0.1f}, .min = 0, .max = 1,
     .group = FC_GROUP_SHADING, .option = "--depth-dimming", .metavar = "D",
     .help = "how much what shows through thick water dims (63% of it at 12 particle radii of thickness), so a "
             "body's far faces read; 0 = off"},
    /* 1: a disc as opaque as foam_pass.c allows; the threshold is the frame's own (foam_classes.h). */
    {FIELD(59, aerated_foam, FC_SETTING_FLOAT, 1), .initial = {0.0f}, .min = 0, .max = 1,
     .group = FC_GROUP_SURFACE, .option = "--aerated-foam", .metavar = "S",
     .help = "white foam, soft-edged, where the flow traps air (converging neighbours, Ihmsen et al. 2012; "
             "needs velocities and --spray-neighbours > 0), this opaque; 0 = off"},
};

#define TABLE_LENGTH (sizeof table / sizeof table[0])

const fc_setting_spec *fc_settings_table(size_t *count)
{
    *count = TABLE_LENGTH;
    return table;
}

const fc_setting_spec *fc_setting_by_key(uint32_t key)
{
    for (size_t i = 0; i < TABLE_LENGTH; i++)
        if (table[i].key == key)
            return &table[i];
    return NULL;
}

const fc_setting_spec *fc_setting_by_name(const char *name)
{
    for (size_t i = 0; i < TABLE_LENGTH; i++)
        if (strcmp(table[i].name, name) == 0)
            return &table[i];
    return NULL;
}

const fc_setting_spec *fc_setting_by_option(const char *option)
{
    for (size_t i = 0; i < TABLE_LENGTH; i++)
        if (table[i].option && strcmp(table[i].option, option) == 0)
            return &table[i];
    return NULL;
}

void *fc_setting_field(const fc_setting_spec *spec, fc_settings *s)
{
    return (char *)s + spec->offset;
}

const void *fc_setting_field_const(const fc_setting_spec *spec, const fc_settings *s)
{
    return (const char *)s + spec->offset;
}

uint32_t fc_setting_choice_count(const fc_setting_spec *spec)
{
    uint32_t n = 0;
    if (spec->type == FC_SETTING_CHOICE)
        while (spec->choices[n])
            n++;
    return n;
}

fc_radius_source fc_radius_source_of(const fc_settings *s, bool frame_has_radii)
{
    if (s->radius > 0.0f)
        return FC_RADIUS_FROM_SETTINGS;
    return frame_has_radii ? FC_RADIUS_PER_PARTICLE : FC_RADIUS_ESTIMATED;
}

uint32_t fc_smoothing_default_iterations(fc_smoothing method)
{
    /* Chosen by eye on the sample scenes at 640x480 (docs/gallery): enough to
     * hide the individual spheres without melting detail. */
    switch (method) {
    case FC_SMOOTHING_CURVATURE: return 60;
    case FC_SMOOTHING_BILATERAL: return 2;
    case FC_SMOOTHING_BINOMIAL: return 8;
    case FC_SMOOTHING_NARROW: return 4;
    case FC_SMOOTHING_NONE: break;
    }
    return 0;
}

void fc_settings_default(fc_settings *s)
{
    memset(s, 0, sizeof *s);
    for (size_t i = 0; i < TABLE_LENGTH; i++) {
        const fc_setting_spec *spec = &table[i];
        void *field = fc_setting_field(spec, s);
        if (spec->type == FC_SETTING_FLOAT || spec->type == FC_SETTING_SCALE)
            memcpy(field, spec->initial, spec->count * sizeof(float));
        else
            *(uint32_t *)field = (uint32_t)spec->initial[0];
    }
}

/* NaN fails every comparison, so this also rejects non-finite values. */
static bool in_domain(const fc_setting_spec *spec, double v)
{
    bool above = spec->flags & FC_SETTING_MIN_OPEN ? v > spec->min : v >= spec->min;
    bool below = spec->flags & FC_SETTING_MAX_OPEN ? v < spec->max : v <= spec->max;
    return above && below;
}

/* What a value outside the domain is told: "is outside [1, 3]", "is outside
 * [0, 1)", "must be finite and > 0" (a domain without a practical upper end). */
static void domain_text(const fc_setting_spec *spec, char *out, size_t size)
{
    bool min_open = spec->flags & FC_SETTING_MIN_OPEN, max_open = spec->flags & FC_SETTING_MAX_OPEN;
    if (spec->max >= FLT_MAX && spec->min <= -FLT_MAX)
        snprintf(out, size, "must be finite");
    else if (spec->max >= FLT_MAX)
        snprintf(out, size, "must be finite and %s %g", min_open ? ">" : ">=", spec->min);
    else
        snprintf(out, size, "is outside %c%g, %g%c", min_open ? '(' : '[', spec->min, spec->max, max_open ? ')' : ']');
}

static fc_code validate_floats(const fc_setting_spec *spec, const float *v, fc_error *err)
{
    for (uint32_t c = 0; c < spec->count; c++) {
        if (in_domain(spec, v[c]))
            continue;
        char domain[64], name[64];
        domain_text(spec, domain, sizeof domain);
        if (spec->count == 1)
            snprintf(name, sizeof name, "%s", spec->name);
        else
            snprintf(name, sizeof name, "%s[%u]", spec->name, c);
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s %g %s", name, (double)v[c], domain);
    }
    return FC_OK;
}

/* The passes render at full, half or quarter resolution, nothing in between. */
static fc_code validate_scale(const fc_setting_spec *spec, float v, fc_error *err)
{
    if (v == 1.0f || v == 0.5f || v == 0.25f)
        return FC_OK;
    return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s %g is not 1, 0.5 or 0.25", spec->name, (double)v);
}

static fc_code validate_choice(const fc_setting_spec *spec, uint32_t v, fc_error *err)
{
    uint32_t n = fc_setting_choice_count(spec);
    if (v < n)
        return FC_OK;
    char names[256] = "";
    for (uint32_t i = 0; i < n; i++) {
        size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s%u (%s)", i ? ", " : "", i, spec->choices[i]);
    }
    return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown %s %u: one of %s", spec->name, v, names);
}

fc_code fc_setting_validate(const fc_setting_spec *spec, const fc_settings *s, fc_error *err)
{
    const void *field = fc_setting_field_const(spec, s);
    switch (spec->type) {
    case FC_SETTING_FLOAT: return validate_floats(spec, field, err);
    case FC_SETTING_SCALE: return validate_scale(spec, *(const float *)field, err);
    case FC_SETTING_CHOICE: return validate_choice(spec, *(const uint32_t *)field, err);
    case FC_SETTING_UINT: {
        uint32_t v = *(const uint32_t *)field;
        if (in_domain(spec, v))
            return FC_OK;
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s %u is outside [%g, %g]", spec->name, v, spec->min,
                            spec->max);
    }
    }
    return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s has an unknown type", spec->name);
}

/* The range maps to the colormap with a finite, positive width (its width is
 * a divisor in the shader) when it is used; without colouring it need only be
 * finite (the table's domain), so zeroed settings stay valid. */
static fc_code validate_coloring(const fc_settings *s, fc_error *err)
{
    float lo = s->color_range[0], hi = s->color_range[1];
    if (!isfinite(hi - lo))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "color_range [%g, %g] must have a finite width", (double)lo,
                            (double)hi);
    if (s->color_by != FC_COLOR_BY_NONE && !(lo < hi))
        return fc_error_set(err, FC_ERR_INVALID_VALUE,
                            "color_range [%g, %g]: min must be below max to colour by an attribute", (double)lo,
                            (double)hi);
    return FC_OK;
}

fc_code fc_settings_validate(const fc_settings *s, fc_error *err)
{
    for (size_t i = 0; i < TABLE_LENGTH; i++) {
        fc_code code = fc_setting_validate(&table[i], s, err);
        if (code != FC_OK)
            return code;
    }
    return validate_coloring(s, err);
}
