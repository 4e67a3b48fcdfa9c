/* reader_hdf5.c — HDF5 particle files, read by libhdf5 from the bytes in memory
 * (the core driver over a file image), in the layouts the SPH codes write:
 *
 * - SWIFT and GADGET snapshots: group PartType0 (the gas) with Coordinates (N x 3),
 *   Velocities (N x 3), Density, SmoothingLength and ParticleIDs, float32 or float64
 *   (GADGET's Header group and its attributes are not needed).
 * - PySPH output (pysph/solver/output.py, HDFOutput): particles/<array>/arrays/<property>,
 *   one 1-D dataset per property: x y z, u v w, rho, h, m, p, tag, gid, ...; every particle
 *   array (fluid, solid, ...) is read, one after the other.
 * - H5Part: groups Step#0, Step#1, ... each with x y z (and any other 1-D arrays); the
 *   lowest-numbered step unless --step names one.
 * - Anything else through --dataset: a group read like the above, an N x 3 dataset of
 *   positions, or "x=PATH,y=PATH,z=PATH".
 *
 * libhdf5 prints its error stack by default: that is turned off, and its innermost
 * reason goes into the fc_error instead. */
#include "reader_formats.h"

#include <hdf5.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "fc_frame.h"
#include "particle_reader.h"
#include "reader_extras.h"
#include "reader_fields.h"
#include "reader_hdf5_table.h"

enum { H5_MAX_ARRAYS = 64 };

typedef struct h5_tables {
    size_t count;
    h5_table items[H5_MAX_ARRAYS];
} h5_tables;

/* ---- the file ---- */

/* The core driver with the bytes as its file image: libhdf5 copies them, so the buffer stays read-only.
 * The core driver refuses a name that exists on disk, so the image gets one that cannot. */
static fc_code open_image(const h5_source *s, const uint8_t *data, hid_t *file, fc_error *err)
{
    static const char image_name[] = "/nonexistent/fluidcast-hdf5-image";
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    bool ready = fapl >= 0 && H5Pset_fapl_core(fapl, 1 << 16, false) >= 0 &&
                 H5Pset_file_image(fapl, (void *)(uintptr_t)data, s->size) >= 0;
    *file = ready ? H5Fopen(image_name, H5F_ACC_RDONLY, fapl) : -1;
    fc_code code = *file >= 0 ? FC_OK : h5_fail(s, err, "not a readable HDF5 file"); /* before H5Pclose clears */
    if (fapl >= 0)
        H5Pclose(fapl);
    return code;
}

static bool has_group(hid_t loc, const char *path)
{
    if (H5Lexists(loc, path, H5P_DEFAULT) <= 0) {
        H5Eclear2(H5E_DEFAULT);
        return false;
    }
    H5O_info_t info;
    bool group = H5Oget_info_by_name(loc, path, &info, H5P_DEFAULT) >= 0 && info.type == H5O_TYPE_GROUP;
    H5Eclear2(H5E_DEFAULT);
    return group;
}

static fc_code read_group_at(const h5_source *s, hid_t file, const char *path, h5_tables *tables, fc_error *err)
{
    if (tables->count == H5_MAX_ARRAYS)
        return fc_error_set(err, FC_ERR_PARSE, "%s: more than %d particle groups", s->name, H5_MAX_ARRAYS);
    hid_t group = H5Gopen2(file, path, H5P_DEFAULT);
    if (group < 0) {
        char what[300];
        snprintf(what, sizeof what, "cannot open group '%s'", path);
        return h5_fail(s, err, what);
    }
    fc_code code = h5_table_read_group(s, group, path, &tables->items[tables->count], err);
    tables->count++; /* freed with the others even when partly read */
    H5Gclose(group);
    return code;
}

/* ---- layouts ---- */

typedef struct h5_names {
    size_t count;
    char names[H5_MAX_ARRAYS][64];
} h5_names;

static herr_t collect_group(hid_t loc, const char *name, const H5L_info_t *info, void *data)
{
    (void)info;
    h5_names *names = data;
    if (names->count < H5_MAX_ARRAYS && strlen(name) < sizeof names->names[0] && has_group(loc, name))
        snprintf(names->names[names->count++], sizeof names->names[0], "%s", name);
    return 0;
}

/* PySPH: every particles/<array> that has an arrays group, in name order. */
static fc_code read_pysph(const h5_source *s, hid_t file, h5_tables *tables, fc_error *err)
{
    h5_names names = { 0, { { 0 } } };
    hid_t particles = H5Gopen2(file, "particles", H5P_DEFAULT);
    if (particles < 0 || H5Literate(particles, H5_INDEX_NAME, H5_ITER_INC, NULL, collect_group, &names) < 0) {
        if (particles >= 0)
            H5Gclose(particles);
        return h5_fail(s, err, "cannot list group 'particles'");
    }
    H5Gclose(particles);
    fc_code code = FC_OK;
    for (size_t i = 0; i < names.count && code == FC_OK; i++) {
        char path[128];
        snprintf(path, sizeof path, "/particles/%s/arrays", names.names[i]);
        if (has_group(file, path))
            code = read_group_at(s, file, path, tables, err);
    }
    if (code == FC_OK && tables->count == 0)
        code = fc_error_set(err, FC_ERR_PARSE, "%s: group 'particles' has no particle array with an 'arrays' group",
                            s->name);
    return code;
}

/* "Step#<n>" with n a decimal number. */
static bool step_number(const char *name, uint64_t *n)
{
    if (strncmp(name, "Step#", 5) != 0 || name[5] < '0' || name[5] > '9')
        return false;
    char *end = NULL;
    unsigned long long value = strtoull(name + 5, &end, 10);
    *n = value;
    return *end == '\0';
}

typedef struct h5_steps {
    bool any, wanted_found, has_wanted;
    uint64_t wanted, lowest;
} h5_steps;

static herr_t scan_step(hid_t loc, const char *name, const H5L_info_t *info, void *data)
{
    (void)loc, (void)info;
    h5_steps *steps = data;
    uint64_t n;
    if (!step_number(name, &n))
        return 0;
    if (!steps->any || n < steps->lowest)
        steps->lowest = n;
    steps->any = true;
    if (steps->has_wanted && n == steps->wanted)
        steps->wanted_found = true;
    return 0;
}

/* H5Part: Step#N, the lowest N unless --step names one. *found false when the file has no step. */
static fc_code read_h5part(const h5_source *s, hid_t file, const fc_read_options *o, h5_tables *tables,
                           bool *found, fc_error *err)
{
    h5_steps steps = { false, false, o->has_step, o->step, 0 };
    if (H5Literate(file, H5_INDEX_NAME, H5_ITER_INC, NULL, scan_step, &steps) < 0)
        return h5_fail(s, err, "cannot list the root group");
    *found = steps.any;
    if (!steps.any)
        return FC_OK;
    if (o->has_step && !steps.wanted_found)
        return fc_error_set(err, FC_ERR_PARSE, "%s: no group Step#%" PRIu64 " (the first step is Step#%" PRIu64 ")",
                            s->name, o->step, steps.lowest);
    char path[64];
    snprintf(path, sizeof path, "/Step#%" PRIu64, o->has_step ? o->step : steps.lowest);
    return read_group_at(s, file, path, tables, err);
}

/* --dataset "x=P,y=P,z=P": three 1-D datasets. */
static fc_code read_components_spec(const h5_source *s, hid_t file, const char *spec, h5_tables *tables,
                                    fc_error *err)
{
    char copy[1024], *paths[3] = { NULL, NULL, NULL };
    if (snprintf(copy, sizeof copy, "%s", spec) >= (int)sizeof copy)
        return fc_error_set(err, FC_ERR_USAGE, "%s: --dataset '%.60s...' is too long", s->name, spec);
    char *save = NULL;
    for (char *part = strtok_r(copy, ",", &save); part != NULL; part = strtok_r(NULL, ",", &save)) {
        int axis = (part[0] == 'x' || part[0] == 'y' || part[0] == 'z') && part[1] == '=' ? part[0] - 'x' : -1;
        if (axis < 0 || paths[axis] != NULL || part[2] == '\0')
            return fc_error_set(err, FC_ERR_USAGE, "%s: --dataset '%s': expected x=PATH,y=PATH,z=PATH", s->name,
                                spec);
        paths[axis] = part + 2;
    }
    if (!paths[0] || !paths[1] || !paths[2])
        return fc_error_set(err, FC_ERR_USAGE, "%s: --dataset '%s': expected x=PATH,y=PATH,z=PATH", s->name, spec);
    tables->count = 1;
    return h5_table_read_positions(s, file, (const char *const *)paths, 3, &tables->items[0], err);
}

/* --dataset PATH: a group like PartType0, or an N x 3 dataset of positions. */
static fc_code read_dataset_spec(const h5_source *s, hid_t file, const char *spec, h5_tables *tables, fc_error *err)
{
    if (strchr(spec, '=') != NULL)
        return read_components_spec(s, file, spec, tables, err);
    if (H5Lexists(file, spec, H5P_DEFAULT) <= 0 && strcmp(spec, "/") != 0) {
        H5Eclear2(H5E_DEFAULT);
        return fc_error_set(err, FC_ERR_PARSE, "%s: --dataset '%s': no such group or dataset", s->name, spec);
    }
    if (has_group(file, spec))
        return read_group_at(s, file, spec, tables, err);
    const char *paths[1] = { spec };
    tables->count = 1;
    return h5_table_read_positions(s, file, paths, 1, &tables->items[0], err);
}

static fc_code read_layout(const h5_source *s, hid_t file, const fc_read_options *o, h5_tables *tables,
                           fc_error *err)
{
    if (o->dataset != NULL)
        return read_dataset_spec(s, file, o->dataset, tables, err);
    if (has_group(file, "PartType0"))
        return read_group_at(s, file, "/PartType0", tables, err);
    if (has_group(file, "particles"))
        return read_pysph(s, file, tables, err);
    bool found = false;
    fc_code code = read_h5part(s, file, o, tables, &found, err);
    if (code != FC_OK || found)
        return code;
    code = read_group_at(s, file, "/", tables, err);
    if (code == FC_ERR_PARSE && tables->items[0].no_positions)
        return fc_error_set(err, FC_ERR_PARSE, "%s: no particles found: expected PartType0 (SWIFT/GADGET), "
                            "particles/*/arrays (PySPH), Step#N (H5Part) or x, y, z at the root; name them with "
                            "--dataset", s->name);
    return code;
}

/* ---- into the frame ---- */

/* The render radius from the SPH smoothing length h. SWIFT sets h = eta x the mean particle spacing with
 * eta = 1.2348 (its default resolution, about 48 neighbours for the cubic spline; GADGET's h is the kernel's
 * support, larger, and PySPH's h = hdx x dx with hdx 1 to 1.3), and fluidcast's radius for a spacing d is
 * 0.9 d (fc_frame_estimate_radius: spheres that just close the surface). So radius = 0.9 h / 1.2348:
 * SWIFT's particles get the size the spacing estimate would give them, adaptively; --radius overrides. */
#define H5_RADIUS_PER_SMOOTHING_LENGTH (0.9 / 1.2348)

/* An attribute is kept when every particle array has it (PySPH's fluid and solid arrays). */
static uint32_t common_attributes(const h5_tables *tables, uint64_t *count)
{
    bool velocity = true, density = true, ids = true, radius = true;
    *count = 0;
    for (size_t i = 0; i < tables->count; i++) {
        const h5_table *t = &tables->items[i];
        velocity = velocity && t->velocity;
        density = density && t->density;
        radius = radius && t->radius;
        ids = ids && t->ids && tables->count == 1; /* ids of two arrays may collide */
        *count += t->count;
    }
    return (density ? FC_ATTR_DENSITY : 0u) | (velocity ? FC_ATTR_VELOCITY : 0u) | (ids ? FC_ATTR_IDS : 0u) |
           (radius ? FC_ATTR_RADIUS : 0u);
}

static fc_code reject(const h5_source *s, fc_error *err, uint64_t index, fc_field field, double value)
{
    const char *requirement = field == FC_FIELD_ID ? "an integer in 0..4294967295" : "a finite value in float range";
    return fc_error_set(err, FC_ERR_PARSE, "%s: particle %llu: %s = %g is not %s", s->name, (unsigned long long)index,
                        fc_field_name(field), value, requirement);
}

/* f64: some array's positions are float64, so all of them wait in double for the recentring. */
static fc_code store_table(const fc_cursor *c, const h5_source *s, const h5_table *t, uint64_t first, bool f64,
                           fc_frame *frame, fc_error *err)
{
    for (uint64_t i = 0; i < t->count; i++) {
        uint64_t at = first + i;
        for (int k = 0; k < 3; k++) {
            fc_field axis = (fc_field)(FC_FIELD_X + k), speed = (fc_field)(FC_FIELD_VX + k);
            double p = t->position[3 * i + (uint64_t)k];
            if (!(f64 ? fc_field_store_position64(c, frame, at, axis, p) : fc_field_store(frame, at, axis, p)))
                return reject(s, err, at, axis, t->position[3 * i + (uint64_t)k]);
            if (frame->velocity && !fc_field_store(frame, at, speed, t->velocity[3 * i + (uint64_t)k]))
                return reject(s, err, at, speed, t->velocity[3 * i + (uint64_t)k]);
        }
        if (frame->density && !fc_field_store(frame, at, FC_FIELD_DENSITY, t->density[i]))
            return reject(s, err, at, FC_FIELD_DENSITY, t->density[i]);
        if (frame->ids && !fc_field_store(frame, at, FC_FIELD_ID, t->ids[i]))
            return reject(s, err, at, FC_FIELD_ID, t->ids[i]);
        if (frame->radius) {
            double r = t->radius[i] * H5_RADIUS_PER_SMOOTHING_LENGTH;
            if (!(r > 0.0 && r <= FC_FRAME_MAX_RADIUS))
                return fc_error_set(err, FC_ERR_PARSE, "%s: particle %llu: smoothing length %g is not in (0, %g]",
                                    s->name, (unsigned long long)at, t->radius[i],
                                    FC_FRAME_MAX_RADIUS / H5_RADIUS_PER_SMOOTHING_LENGTH);
            frame->radius[at] = (float)r;
        }
    }
    return FC_OK;
}

/* The named scalars every table has, concatenated, for --select. */
static fc_code store_extras(const fc_cursor *c, const h5_tables *tables, fc_error *err)
{
    const h5_table *first = &tables->items[0];
    for (size_t k = 0; c->extras != NULL && k < first->extra_count; k++) {
        const double *parts[H5_MAX_ARRAYS];
        uint64_t count = 0;
        size_t found = 0;
        for (size_t i = 0; i < tables->count; i++) {
            const h5_table *t = &tables->items[i];
            for (size_t j = 0; j < t->extra_count && found == i; j++)
                if (strcmp(t->extra_names[j], first->extra_names[k]) == 0)
                    parts[found++] = t->extras[j];
            count += t->count;
        }
        if (found != tables->count)
            continue;
        fc_code code = FC_OK;
        fc_span name = { first->extra_names[k], strlen(first->extra_names[k]) };
        double *values = fc_extras_add(c->extras, name, count, c->name, err, &code);
        if (code != FC_OK)
            return code;
        for (size_t i = 0, at = 0; values && i < tables->count; at += tables->items[i].count, i++)
            memcpy(values + at, parts[i], (size_t)tables->items[i].count * sizeof *values);
    }
    return FC_OK;
}

static fc_code store_tables(const fc_cursor *c, const h5_source *s, const h5_tables *tables, fc_frame *frame,
                            fc_error *err)
{
    uint64_t count = 0;
    uint32_t attributes = common_attributes(tables, &count);
    fc_code code = fc_reader_alloc_frame(c, frame, count, attributes, err);
    uint64_t first = 0;
    bool f64 = false;
    for (size_t i = 0; i < tables->count; i++)
        f64 = f64 || tables->items[i].position_value_size > 4;
    for (size_t i = 0; i < tables->count && code == FC_OK; i++) {
        code = store_table(c, s, &tables->items[i], first, f64, frame, err);
        first += tables->items[i].count;
    }
    return code == FC_OK ? store_extras(c, tables, err) : code;
}

fc_code fc_read_hdf5(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    h5_source s = { c->name, c->size };
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors come back as values, not printed by libhdf5 */
    hid_t file = -1;
    fc_code code = open_image(&s, c->data, &file, err);
    if (code != FC_OK)
        return code;
    h5_tables *tables = calloc(1, sizeof *tables);
    code = tables ? read_layout(&s, file, c->options, tables, err)
                  : fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", c->name);
    if (code == FC_OK)
        code = store_tables(c, &s, tables, frame, err);
    for (size_t i = 0; tables && i < tables->count; i++)
        h5_table_free(&tables->items[i]);
    free(tables);
    H5Fclose(file);
    H5Eclear2(H5E_DEFAULT);
    return code;
}
