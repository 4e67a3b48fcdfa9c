/* fc_settings.h — the render settings' table: every fact about each field of
 * fc_settings (its SETTINGS key, type, default, domain, command-line option and
 * help line) written once. Defaults, validation, the wire codec, the command
 * line's options and help and the Python binding's fields all come from it, so
 * a new setting is one entry here plus its use in the renderer.
 *
 * This header is public (installed next to fluidcast.h): a binding or a tool
 * can walk the table to learn every setting the library knows. */
#ifndef FLUIDCAST_SETTINGS_H
#define FLUIDCAST_SETTINGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fc_api.h"
#include "fc_error.h"
#include "fluidcast_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How a setting's value is stored and what it may be. Every field is 4 bytes
 * per value (float, uint32_t, or an enum the compiler stores as an int). */
typedef enum fc_setting_type {
    FC_SETTING_FLOAT = 1,  /* `count` floats, each in the domain [min, max] */
    FC_SETTING_UINT = 2,   /* one uint32_t in [min, max] */
    FC_SETTING_CHOICE = 3, /* one uint32_t or enum: an index into `choices` */
    FC_SETTING_SCALE = 4   /* one float, a pass's resolution: 1, 0.5 or 0.25 */
} fc_setting_type;

/* Bits of fc_setting_spec.flags. */
enum {
    FC_SETTING_MIN_OPEN = 1u << 0,  /* the domain excludes min: (min, max] */
    FC_SETTING_MAX_OPEN = 1u << 1,  /* the domain excludes max: [min, max) */
    FC_SETTING_CLI_POSITIVE = 1u << 2, /* the command line takes only values > 0 (0 = leave the option out) */
    FC_SETTING_PER_SMOOTHING = 1u << 3, /* the default depends on the smoothing method
                                           (fc_smoothing_default_iterations) */
    FC_SETTING_FROM_FRAME = 1u << 4, /* left out, the command line chooses it from the particles (the help
                                        says how); `initial` is the wire's default */
    FC_SETTING_RANGE = 1u << 5       /* two values MIN, MAX: the command line wants MIN < MAX */
};

/* The parts of the command line's help the settings are listed under. */
typedef enum fc_setting_group {
    FC_GROUP_SURFACE = 0,   /* the fluid's surface: particles, smoothing, spray */
    FC_GROUP_SHADING = 1,   /* light, colour and the scene */
    FC_GROUP_COLORING = 2,  /* colour by attribute */
    FC_GROUP_IMAGE = 3,     /* the encoded image */
    FC_GROUP_COUNT
} fc_setting_group;

/* One setting: plain data, every field documented. */
typedef struct fc_setting_spec {
    const char *name;            /* the fc_settings field; also the Python keyword and the key's name */
    uint16_t key;                /* the SETTINGS message's key (PROTOCOL.md 7.5) */
    fc_setting_type type;
    uint32_t count;              /* values of the field: 1, 2 (a range) or 3 (a colour) */
    size_t offset;               /* offsetof(fc_settings, name) */
    float initial[3];            /* fc_settings_default's value(s); a CHOICE's index as a float */
    double min, max;             /* FLOAT, UINT: the domain, closed unless flags open an end */
    uint32_t flags;              /* FC_SETTING_* bits */
    const char *const *choices;  /* CHOICE: the names of values 0, 1, ..., ending with NULL */
    char separator;              /* between values on the command line: ',' or ':' (count > 1) */
    fc_setting_group group;
    const char *option;          /* the command-line option, "--ior" */
    const char *metavar;         /* what its value is called in the help, "N" */
    const char *help;            /* one sentence for the help, without the domain or default */
} fc_setting_spec;

/* Where a render's sphere radius comes from (PROTOCOL.md 5). */
typedef enum fc_radius_source {
    FC_RADIUS_FROM_SETTINGS = 0,  /* the settings' radius, > 0: every particle's, overriding any per-particle radii */
    FC_RADIUS_PER_PARTICLE = 1,   /* radius 0 and a frame with radii: each particle's own */
    FC_RADIUS_ESTIMATED = 2       /* radius 0 and a frame without: estimated from the particle spacing
                                     (fc_frame_estimate_radius) */
} fc_radius_source;

/* The rule every side applies to a radius setting and a frame (the CLI to
 * say what it chose, the daemon to estimate once per frame, the pipeline to
 * refuse an unresolved radius): written here once. */
FC_API fc_radius_source fc_radius_source_of(const fc_settings *s, bool frame_has_radii);

/* The table, in key order, and its length in *count. Never NULL. */
FC_API const fc_setting_spec *fc_settings_table(size_t *count);

/* The setting with SETTINGS key `key`, NULL for a reserved or unknown key. */
FC_API const fc_setting_spec *fc_setting_by_key(uint32_t key);

/* The setting called `name` (a field name, "ior"), NULL for none. */
FC_API const fc_setting_spec *fc_setting_by_name(const char *name);

/* The setting whose command-line option is `option` ("--ior"), NULL for none. */
FC_API const fc_setting_spec *fc_setting_by_option(const char *option);

/* Default settings that make convincing water: radius 0 (auto), the
 * narrow-range filter with its default iterations, a blue-green tint, ior 1.33
 * (every field from the table's `initial`). */
FC_API void fc_settings_default(fc_settings *s);

/* Iterations that suit each smoothing method: the methods count different
 * things (curvature-flow time steps vs passes of a filter), so one number
 * cannot serve all. 0 for FC_SMOOTHING_NONE. */
FC_API uint32_t fc_smoothing_default_iterations(fc_smoothing method);

/* Checks every field against its domain in the table, then the rules between
 * fields (a colour range to colour by). FC_ERR_INVALID_VALUE naming the field,
 * its value and what it may be. */
FC_API fc_code fc_settings_validate(const fc_settings *s, fc_error *err);

/* Checks one setting's value(s) as stored in `s`. */
FC_API fc_code fc_setting_validate(const fc_setting_spec *spec, const fc_settings *s, fc_error *err);

/* The field's storage in `s` (spec->count values of 4 bytes). */
FC_API void *fc_setting_field(const fc_setting_spec *spec, fc_settings *s);
FC_API const void *fc_setting_field_const(const fc_setting_spec *spec, const fc_settings *s);

/* The number of names of a CHOICE setting (0 for other types). */
FC_API uint32_t fc_setting_choice_count(const fc_setting_spec *spec);

#ifdef __cplusplus
}
#endif

#endif
