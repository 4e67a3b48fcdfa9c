/* reader_hdf5_table.c — see reader_hdf5_table.h. */
#include "reader_hdf5_table.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_cursor.h"

/* The most a value can shrink in a file: deflate's limit is about 1032:1, and a dataset's
 * values cannot come from fewer bytes, so a shape that claims more is refused unread. */
enum { H5_MAX_EXPANSION = 1032, H5_MAX_LINKS = 256 };

typedef enum h5_role { H5_EXTRA, H5_POSITION, H5_VELOCITY, H5_DENSITY, H5_RADIUS, H5_ID, H5_ROLE_COUNT } h5_role;

static const char *const role_names[H5_ROLE_COUNT] = { "extra", "positions", "velocity", "density",
                                                       "smoothing length", "ids" };

/* component -1: an N x 3 dataset of all three. */
static const struct {
    const char *name;
    h5_role role;
    int component;
} known_names[] = {
    { "Coordinates", H5_POSITION, -1 }, { "Positions", H5_POSITION, -1 }, { "Position", H5_POSITION, -1 },
    { "x", H5_POSITION, 0 },            { "y", H5_POSITION, 1 },          { "z", H5_POSITION, 2 },
    { "Velocities", H5_VELOCITY, -1 },  { "Velocity", H5_VELOCITY, -1 },  { "vx", H5_VELOCITY, 0 },
    { "vy", H5_VELOCITY, 1 },           { "vz", H5_VELOCITY, 2 },         { "u", H5_VELOCITY, 0 },
    { "v", H5_VELOCITY, 1 },            { "w", H5_VELOCITY, 2 },          { "Density", H5_DENSITY, 0 },
    { "Densities", H5_DENSITY, 0 },     { "rho", H5_DENSITY, 0 },         { "SmoothingLength", H5_RADIUS, 0 },
    { "SmoothingLengths", H5_RADIUS, 0 }, { "h", H5_RADIUS, 0 },          { "ParticleIDs", H5_ID, 0 },
    { "id", H5_ID, 0 },                 { "ids", H5_ID, 0 },
};

/* ---- libhdf5's reasons ---- */

typedef struct h5_reason {
    char text[160];
    bool found;
} h5_reason;

/* Walking upward starts at the innermost error: where libhdf5 saw the problem. */
static herr_t keep_innermost(unsigned n, const H5E_error2_t *e, void *data)
{
    (void)n;
    h5_reason *r = data;
    if (!r->found && e->desc != NULL) {
        snprintf(r->text, sizeof r->text, "%s", e->desc);
        r->found = true;
    }
    return 0;
}

fc_code h5_fail(const h5_source *s, fc_error *err, const char *what)
{
    h5_reason reason = { "", false };
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &reason);
    H5Eclear2(H5E_DEFAULT);
    if (!reason.found || reason.text[0] == '\0')
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s", s->name, what);
    return fc_error_set(err, FC_ERR_PARSE, "%s: %s: %s", s->name, what, reason.text);
}

/* ---- one dataset ---- */

typedef struct h5_shape {
    int rank;
    hsize_t dims[2];
    size_t value_size;
} h5_shape;

/* Numeric class, simple dataspace of rank 1 or 2: anything else is no particle array. */
static fc_code dataset_shape(const h5_source *s, hid_t d, const char *path, h5_shape *shape, fc_error *err)
{
    char what[256];
    snprintf(what, sizeof what, "dataset '%s'", path);
    hid_t type = H5Dget_type(d);
    if (type < 0)
        return h5_fail(s, err, what);
    H5T_class_t cls = H5Tget_class(type);
    shape->value_size = H5Tget_size(type);
    H5Tclose(type);
    hid_t space = H5Dget_space(d);
    if (space < 0)
        return h5_fail(s, err, what);
    shape->rank = H5Sget_simple_extent_ndims(space);
    if (shape->rank >= 1 && shape->rank <= 2)
        H5Sget_simple_extent_dims(space, shape->dims, NULL);
    H5Sclose(space);
    if (cls != H5T_INTEGER && cls != H5T_FLOAT)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s is not numeric", s->name, what);
    if (shape->rank < 1 || shape->rank > 2)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s has rank %d: expected (N,) or (N, 3)", s->name, what,
                            shape->rank);
    if (shape->rank == 1)
        shape->dims[1] = 1;
    return FC_OK;
}

/* Whether the shape is (N,) [columns 1, also (N, 1)] or (N, 3) [columns 3]. */
static bool shape_has_columns(const h5_shape *shape, size_t columns)
{
    return columns == 1 ? shape->dims[1] == 1 : shape->rank == 2 && shape->dims[1] == 3;
}

static fc_code check_shape(const h5_source *s, const h5_shape *shape, const char *path, size_t columns,
                           uint64_t rows, fc_error *err)
{
    if (!shape_has_columns(shape, columns)) {
        char second[32] = "";
        if (shape->rank == 2)
            snprintf(second, sizeof second, ", %llu", (unsigned long long)shape->dims[1]);
        return fc_error_set(err, FC_ERR_PARSE, "%s: dataset '%s' has shape (%llu%s): expected (N%s)", s->name, path,
                            (unsigned long long)shape->dims[0], second, columns == 3 ? ", 3" : ",");
    }
    if (rows != 0 && shape->dims[0] != rows)
        return fc_error_set(err, FC_ERR_PARSE, "%s: dataset '%s' holds %llu particles, the positions %llu", s->name,
                            path, (unsigned long long)shape->dims[0], (unsigned long long)rows);
    if (shape->dims[0] == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: dataset '%s': no particles", s->name, path);
    double bytes = (double)shape->dims[0] * (double)columns * (double)shape->value_size;
    if (bytes > (double)s->size * H5_MAX_EXPANSION)
        return fc_error_set(err, FC_ERR_PARSE, "%s: dataset '%s' claims %llu x %zu values: more than a file of %zu "
                            "bytes can hold", s->name, path, (unsigned long long)shape->dims[0], columns, s->size);
    return FC_OK;
}

/* Reads an open dataset of (rows, columns) into a malloc'd array of doubles (libhdf5 converts). */
static fc_code read_values(const h5_source *s, hid_t d, const char *path, uint64_t rows, size_t columns,
                           double **out, fc_error *err)
{
    char what[256];
    snprintf(what, sizeof what, "dataset '%s'", path);
    if (H5Dget_storage_size(d) == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: %s has no values written", s->name, what);
    *out = malloc((size_t)rows * columns * sizeof **out);
    if (*out == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: %s: cannot allocate %llu values", s->name, what,
                            (unsigned long long)rows * columns);
    if (H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out) < 0) {
        free(*out);
        *out = NULL;
        return h5_fail(s, err, what);
    }
    return FC_OK;
}

/* Opens loc/name, checks it is (rows, columns) (rows 0: any, then *rows_out tells) and reads it. */
static fc_code read_dataset(const h5_source *s, hid_t loc, const char *name, const char *path, size_t columns,
                            uint64_t rows, double **out, uint64_t *rows_out, size_t *value_size, fc_error *err)
{
    char what[256];
    hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
    if (d < 0) {
        snprintf(what, sizeof what, "cannot open dataset '%s'", path);
        return h5_fail(s, err, what);
    }
    h5_shape shape;
    fc_code code = dataset_shape(s, d, path, &shape, err);
    if (code == FC_OK)
        code = check_shape(s, &shape, path, columns, rows, err);
    if (code == FC_OK)
        code = read_values(s, d, path, shape.dims[0], columns, out, err);
    if (code == FC_OK && rows_out != NULL)
        *rows_out = shape.dims[0];
    if (code == FC_OK && value_size != NULL && shape.value_size > *value_size)
        *value_size = shape.value_size;
    H5Dclose(d);
    return code;
}

/* ---- a group's datasets ---- */

typedef struct h5_links {
    size_t count;
    char names[H5_MAX_LINKS][H5_NAME_MAX];
} h5_links;

/* The group's datasets (names that fit H5_NAME_MAX; other objects and dangling links left out). */
static herr_t collect_link(hid_t group, const char *name, const H5L_info_t *info, void *data)
{
    (void)info;
    h5_links *links = data;
    if (links->count == H5_MAX_LINKS || strlen(name) >= H5_NAME_MAX)
        return 0;
    hid_t object = H5Oopen(group, name, H5P_DEFAULT);
    if (object < 0) {
        H5Eclear2(H5E_DEFAULT);
        return 0;
    }
    if (H5Iget_type(object) == H5I_DATASET)
        snprintf(links->names[links->count++], H5_NAME_MAX, "%s", name);
    H5Oclose(object);
    return 0;
}

/* Where each role's datasets are: index into links, -1 when absent ([3] for the N x 3 one). */
typedef struct h5_plan {
    int at[H5_ROLE_COUNT][4];
    bool used[H5_MAX_LINKS];
} h5_plan;

static void plan_roles(const h5_links *links, h5_plan *plan)
{
    memset(plan->at, -1, sizeof plan->at);
    memset(plan->used, 0, sizeof plan->used);
    for (size_t k = 0; k < sizeof known_names / sizeof known_names[0]; k++) {
        for (size_t i = 0; i < links->count; i++) {
            fc_span name = { links->names[i], strlen(links->names[i]) };
            int slot = known_names[k].component < 0 ? 3 : known_names[k].component;
            int *at = &plan->at[known_names[k].role][slot];
            if (*at < 0 && !plan->used[i] && fc_span_iequals(name, known_names[k].name)) {
                *at = (int)i;
                plan->used[i] = true;
            }
        }
    }
}

static void join_path(char *out, size_t size, const char *group, const char *name)
{
    size_t n = strlen(group);
    snprintf(out, size, "%s%s%s", group, n > 0 && group[n - 1] == '/' ? "" : "/", name);
}

/* One role: its N x 3 dataset, else its three components; *found false when neither is complete. */
static fc_code read_vector(const h5_source *s, hid_t group, const char *path, const h5_links *links, h5_plan *plan,
                           h5_role role, uint64_t *rows, double **out, size_t *value_size, fc_error *err)
{
    char full[512];
    const int *at = plan->at[role];
    if (at[3] >= 0) {
        join_path(full, sizeof full, path, links->names[at[3]]);
        return read_dataset(s, group, links->names[at[3]], full, 3, *rows, out, rows, value_size, err);
    }
    if (at[0] < 0 || at[1] < 0 || at[2] < 0) {
        for (int k = 0; k < 3; k++) /* an incomplete vector's parts are plain scalars */
            if (at[k] >= 0)
                plan->used[at[k]] = false;
        return FC_OK;
    }
    double *parts[3] = { NULL, NULL, NULL };
    fc_code code = FC_OK;
    for (int k = 0; k < 3 && code == FC_OK; k++) {
        join_path(full, sizeof full, path, links->names[at[k]]);
        code = read_dataset(s, group, links->names[at[k]], full, 1, *rows, &parts[k], rows, value_size, err);
    }
    if (code == FC_OK && (*out = malloc((size_t)*rows * 3 * sizeof **out)) == NULL)
        code = fc_error_set(err, FC_ERR_NOMEM, "%s: cannot allocate %s for %llu particles", s->name,
                            role_names[role], (unsigned long long)*rows);
    for (uint64_t i = 0; code == FC_OK && i < *rows; i++)
        for (int k = 0; k < 3; k++)
            (*out)[3 * i + (uint64_t)k] = parts[k][i];
    for (int k = 0; k < 3; k++)
        free(parts[k]);
    return code;
}

static fc_code read_scalar_role(const h5_source *s, hid_t group, const char *path, const h5_links *links,
                                const h5_plan *plan, h5_role role, uint64_t rows, double **out, fc_error *err)
{
    char full[512];
    int at = plan->at[role][0];
    if (at < 0)
        return FC_OK;
    join_path(full, sizeof full, path, links->names[at]);
    return read_dataset(s, group, links->names[at], full, 1, rows, out, NULL, NULL, err);
}

/* Every other numeric (N,) dataset becomes a named scalar; other shapes are not per-particle and are skipped. */
static fc_code read_extras(const h5_source *s, hid_t group, const char *path, const h5_links *links,
                           const h5_plan *plan, h5_table *t, fc_error *err)
{
    char full[512];
    for (size_t i = 0; i < links->count && t->extra_count < H5_MAX_EXTRAS; i++) {
        if (plan->used[i])
            continue;
        hid_t d = H5Dopen2(group, links->names[i], H5P_DEFAULT);
        if (d < 0) {
            H5Eclear2(H5E_DEFAULT);
            continue;
        }
        h5_shape shape;
        fc_error ignored;
        join_path(full, sizeof full, path, links->names[i]);
        bool per_particle = dataset_shape(s, d, full, &shape, &ignored) == FC_OK && shape.dims[1] == 1 &&
                            shape.dims[0] == t->count;
        H5Eclear2(H5E_DEFAULT);
        fc_code code = per_particle ? read_values(s, d, full, t->count, 1, &t->extras[t->extra_count], err) : FC_OK;
        H5Dclose(d);
        if (code != FC_OK)
            return code;
        if (per_particle)
            snprintf(t->extra_names[t->extra_count++], H5_NAME_MAX, "%s", links->names[i]);
    }
    return FC_OK;
}

fc_code h5_table_read_group(const h5_source *s, hid_t group, const char *path, h5_table *t, fc_error *err)
{
    memset(t, 0, sizeof *t);
    h5_links *links = calloc(1, sizeof *links);
    h5_plan *plan = calloc(1, sizeof *plan);
    fc_code code = links && plan ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", s->name);
    char what[600];
    snprintf(what, sizeof what, "cannot list group '%s'", path);
    if (code == FC_OK && H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, NULL, collect_link, links) < 0)
        code = h5_fail(s, err, what);
    if (code == FC_OK) {
        plan_roles(links, plan);
        code = read_vector(s, group, path, links, plan, H5_POSITION, &t->count, &t->position,
                           &t->position_value_size, err);
    }
    if (code == FC_OK && t->position == NULL && (t->no_positions = true))
        code = fc_error_set(err, FC_ERR_PARSE, "%s: group '%s' has no positions (Coordinates as N x 3, or x, y "
                            "and z)", s->name, path);
    if (code == FC_OK)
        code = read_vector(s, group, path, links, plan, H5_VELOCITY, &t->count, &t->velocity, NULL, err);
    if (code == FC_OK)
        code = read_scalar_role(s, group, path, links, plan, H5_DENSITY, t->count, &t->density, err);
    if (code == FC_OK)
        code = read_scalar_role(s, group, path, links, plan, H5_RADIUS, t->count, &t->radius, err);
    if (code == FC_OK)
        code = read_scalar_role(s, group, path, links, plan, H5_ID, t->count, &t->ids, err);
    if (code == FC_OK)
        code = read_extras(s, group, path, links, plan, t, err);
    free(links);
    free(plan);
    return code;
}

fc_code h5_table_read_positions(const h5_source *s, hid_t file, const char *const *paths, size_t path_count,
                                h5_table *t, fc_error *err)
{
    memset(t, 0, sizeof *t);
    if (path_count == 1)
        return read_dataset(s, file, paths[0], paths[0], 3, 0, &t->position, &t->count, &t->position_value_size,
                            err);
    double *parts[3] = { NULL, NULL, NULL };
    fc_code code = FC_OK;
    for (int k = 0; k < 3 && code == FC_OK; k++)
        code = read_dataset(s, file, paths[k], paths[k], 1, t->count, &parts[k], &t->count, &t->position_value_size,
                            err);
    if (code == FC_OK && (t->position = malloc((size_t)t->count * 3 * sizeof *t->position)) == NULL)
        code = fc_error_set(err, FC_ERR_NOMEM, "%s: cannot allocate positions", s->name);
    for (uint64_t i = 0; code == FC_OK && i < t->count; i++)
        for (int k = 0; k < 3; k++)
            t->position[3 * i + (uint64_t)k] = parts[k][i];
    for (int k = 0; k < 3; k++)
        free(parts[k]);
    return code;
}

void h5_table_free(h5_table *t)
{
    free(t->position);
    free(t->velocity);
    free(t->density);
    free(t->radius);
    free(t->ids);
    for (size_t i = 0; i < t->extra_count; i++)
        free(t->extras[i]);
    memset(t, 0, sizeof *t);
}
