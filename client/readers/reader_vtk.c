/* reader_vtk.c — legacy VTK files (ASCII and big-endian BINARY), DATASET POLYDATA or
 * UNSTRUCTURED_GRID.
 *
 * Two passes: the scan walks every section (cells, cell types, lookup tables,
 * all attribute arrays) at its exact size and remembers where the positions and
 * the density, velocity and id point arrays start; only then, with the
 * attributes known, is the frame allocated and those arrays read. */
#include "reader_formats.h"

#include "fc_error.h"
#include "fc_frame.h"
#include "reader_extras.h"
#include "reader_fields.h"

typedef struct vtk_block {
    bool present;
    fc_cursor at;              /* positioned on the block's first value */
    fc_scalar_type type;
    uint64_t components;
    fc_field first_field;      /* component k feeds first_field + k */
} vtk_block;

typedef enum vtk_section { VTK_DATASET, VTK_POINT_DATA, VTK_CELL_DATA } vtk_section;

typedef struct vtk_file {
    bool have_points;
    uint64_t point_count;
    vtk_section section;
    uint64_t tuples;           /* tuples per attribute array in the current section */
    vtk_block positions, density, velocity, ids, radius;
    /* Other one-component point arrays (DualSPHysics' Type, Mk), kept for --select when the read asks. */
    size_t extra_count;
    vtk_block extras[FC_EXTRAS_MAX];
    fc_span extra_names[FC_EXTRAS_MAX];
} vtk_file;

static const struct {
    const char *name;
    fc_scalar_type type;
} vtk_type_names[] = {
    { "unsigned_char", FC_SCALAR_U8 },   { "char", FC_SCALAR_I8 },
    { "unsigned_short", FC_SCALAR_U16 }, { "short", FC_SCALAR_I16 },
    { "unsigned_int", FC_SCALAR_U32 },   { "int", FC_SCALAR_I32 },
    /* written with the writer's sizeof(long): 8 on the LP64 systems that produce them */
    { "unsigned_long", FC_SCALAR_U64 },  { "long", FC_SCALAR_I64 },
    { "float", FC_SCALAR_F32 },          { "double", FC_SCALAR_F64 },
    /* the legacy writer stores vtkIdType as 32-bit int */
    { "vtkIdType", FC_SCALAR_I32 },
    { "vtktypeint8", FC_SCALAR_I8 },     { "vtktypeuint8", FC_SCALAR_U8 },
    { "vtktypeint16", FC_SCALAR_I16 },   { "vtktypeuint16", FC_SCALAR_U16 },
    { "vtktypeint32", FC_SCALAR_I32 },   { "vtktypeuint32", FC_SCALAR_U32 },
    { "vtktypeint64", FC_SCALAR_I64 },   { "vtktypeuint64", FC_SCALAR_U64 },
    { "vtktypefloat32", FC_SCALAR_F32 }, { "vtktypefloat64", FC_SCALAR_F64 },
};

/* Rhop and Idp are DualSPHysics' names (its Vel is a 3-component SCALARS). */
static const char *const vtk_density_names[] = { "density", "rho", "rhop", NULL };
static const char *const vtk_velocity_names[] = { "velocity", "vel", "v", NULL };
static const char *const vtk_id_names[] = { "id", "ids", "idp", NULL };
static const char *const vtk_radius_names[] = { "radius", "pscale", NULL };

static bool vtk_is_one_of(fc_span name, const char *const *names)
{
    for (; *names != NULL; names++) {
        if (fc_span_iequals(name, *names))
            return true;
    }
    return false;
}

/* ---- keyword line arguments ---- */

static fc_code vtk_arg(const fc_cursor *c, fc_span *rest, const char *what, fc_span *token, fc_error *err)
{
    if (!fc_span_next_token(rest, token))
        return fc_cursor_fail(c, err, "missing %s", what);
    return FC_OK;
}

static fc_code vtk_arg_count(const fc_cursor *c, fc_span *rest, const char *what, uint64_t *count, fc_error *err)
{
    fc_span token;
    fc_code code = vtk_arg(c, rest, what, &token, err);
    if (code == FC_OK && !fc_span_to_count(token, count)) {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "%s '%s' is not a non-negative integer", what,
                              fc_span_quote(token, quoted, sizeof quoted));
    }
    return code;
}

static fc_code vtk_arg_type(const fc_cursor *c, fc_span *rest, fc_scalar_type *type, fc_error *err)
{
    fc_span token;
    fc_code code = vtk_arg(c, rest, "data type", &token, err);
    if (code != FC_OK)
        return code;
    for (size_t i = 0; i < sizeof vtk_type_names / sizeof vtk_type_names[0]; i++) {
        if (fc_span_iequals(token, vtk_type_names[i].name)) {
            *type = vtk_type_names[i].type;
            return FC_OK;
        }
    }
    char quoted[FC_QUOTE_MAX];
    return fc_cursor_fail(c, err, "unsupported data type '%s'", fc_span_quote(token, quoted, sizeof quoted));
}

/* ---- skipping data ---- */

static fc_code vtk_skip_values(fc_cursor *c, uint64_t count, fc_scalar_type type, fc_error *err)
{
    if (c->binary) {
        if (!fc_cursor_skip_items(c, count, fc_scalar_size(type)))
            return fc_cursor_fail(c, err, "%llu values of %zu bytes run past the end of the data",
                                  (unsigned long long)count, fc_scalar_size(type));
        /* The writer ends each binary block with a newline: step over it so the
         * next keyword can be recognised where it starts. */
        if (c->pos < c->size && c->data[c->pos] == '\n')
            c->pos++;
        return FC_OK;
    }
    fc_span token;
    for (uint64_t i = 0; i < count; i++) {
        if (!fc_cursor_next_token(c, &token))
            return fc_cursor_fail(c, err, "expected %llu values, found %llu", (unsigned long long)count,
                                  (unsigned long long)i);
    }
    return FC_OK;
}

static fc_code vtk_multiply(const fc_cursor *c, uint64_t a, uint64_t b, uint64_t *product, fc_error *err)
{
    if (b != 0 && a > UINT64_MAX / b)
        return fc_cursor_fail(c, err, "value count %llu x %llu overflows", (unsigned long long)a,
                              (unsigned long long)b);
    *product = a * b;
    return FC_OK;
}

/* Skips `tuples` x `components` values; when target is given, first records
 * that the array starts here. */
static fc_code vtk_array_data(fc_cursor *c, uint64_t tuples, uint64_t components, fc_scalar_type type,
                              vtk_block *target, fc_error *err)
{
    uint64_t count = 0;
    fc_code code = vtk_multiply(c, tuples, components, &count, err);
    if (code != FC_OK)
        return code;
    if (target != NULL) {
        target->present = true;
        target->at = *c;
        target->type = type;
    }
    return vtk_skip_values(c, count, type, err);
}

/* The particle array a point-data array named `name` provides, or NULL. */
static vtk_block *vtk_point_array_target(vtk_file *f, fc_span name, uint64_t components)
{
    if (f->section != VTK_POINT_DATA)
        return NULL;
    if (components == 1 && vtk_is_one_of(name, vtk_density_names))
        return &f->density;
    if (components == 3 && vtk_is_one_of(name, vtk_velocity_names))
        return &f->velocity;
    if (components == 1 && vtk_is_one_of(name, vtk_id_names))
        return &f->ids;
    if (components == 1 && vtk_is_one_of(name, vtk_radius_names))
        return &f->radius;
    return NULL;
}

/* An attribute array: the particle data when its name says so, skipped otherwise. */
static fc_code vtk_attribute_array(fc_cursor *c, vtk_file *f, fc_span name, uint64_t components, uint64_t tuples,
                                   fc_scalar_type type, bool may_be_particle_data, fc_error *err)
{
    vtk_block *target = may_be_particle_data ? vtk_point_array_target(f, name, components) : NULL;
    if (target == NULL && c->extras != NULL && f->section == VTK_POINT_DATA && components == 1 &&
        tuples == f->point_count && f->extra_count < FC_EXTRAS_MAX) {
        f->extra_names[f->extra_count] = name;
        return vtk_array_data(c, tuples, components, type, &f->extras[f->extra_count++], err);
    }
    if (target != NULL) {
        char quoted[FC_QUOTE_MAX];
        fc_span_quote(name, quoted, sizeof quoted);
        if (target->present)
            return fc_cursor_fail(c, err, "second array for %s ('%s')", fc_field_name(target->first_field), quoted);
        if (tuples != f->point_count)
            return fc_cursor_fail(c, err, "array '%s' has %llu tuples for %llu points", quoted,
                                  (unsigned long long)tuples, (unsigned long long)f->point_count);
    }
    return vtk_array_data(c, tuples, components, type, target, err);
}

/* ---- sections ---- */

static fc_code vtk_points(fc_cursor *c, vtk_file *f, fc_span rest, fc_error *err)
{
    fc_scalar_type type = FC_SCALAR_F32;
    if (f->have_points)
        return fc_cursor_fail(c, err, "second POINTS section");
    fc_code code = vtk_arg_count(c, &rest, "point count", &f->point_count, err);
    if (code == FC_OK)
        code = vtk_arg_type(c, &rest, &type, err);
    if (code != FC_OK)
        return code;
    f->have_points = true;
    return vtk_array_data(c, f->point_count, 3, type, &f->positions, err);
}

/* The next line must be `keyword type`; returns that type. */
static fc_code vtk_typed_line(fc_cursor *c, const char *keyword, fc_scalar_type *type, fc_error *err)
{
    fc_span line, rest, token;
    if (!fc_cursor_next_nonblank_line(c, &line))
        return fc_cursor_fail(c, err, "missing %s line", keyword);
    rest = line;
    if (!fc_span_next_token(&rest, &token) || !fc_span_iequals(token, keyword))
        return fc_cursor_fail(c, err, "expected %s", keyword);
    return vtk_arg_type(c, &rest, type, err);
}

/* CELLS / VERTICES / LINES / POLYGONS / TRIANGLE_STRIPS n size: either the legacy
 * layout (`size` ints) or the 5.x one (OFFSETS with n values, CONNECTIVITY with size). */
static fc_code vtk_cells(fc_cursor *c, fc_span rest, fc_error *err)
{
    uint64_t count = 0, size = 0;
    fc_scalar_type type = FC_SCALAR_I32;
    fc_code code = vtk_arg_count(c, &rest, "cell count", &count, err);
    if (code == FC_OK)
        code = vtk_arg_count(c, &rest, "cell list size", &size, err);
    if (code != FC_OK)
        return code;
    if (!fc_cursor_peek_keyword(c, "OFFSETS"))
        return vtk_skip_values(c, size, FC_SCALAR_I32, err);
    code = vtk_typed_line(c, "OFFSETS", &type, err);
    if (code == FC_OK)
        code = vtk_skip_values(c, count, type, err);
    if (code == FC_OK)
        code = vtk_typed_line(c, "CONNECTIVITY", &type, err);
    if (code == FC_OK)
        code = vtk_skip_values(c, size, type, err);
    return code;
}

static fc_code vtk_cell_types(fc_cursor *c, fc_span rest, fc_error *err)
{
    uint64_t count = 0;
    fc_code code = vtk_arg_count(c, &rest, "cell count", &count, err);
    if (code != FC_OK)
        return code;
    return vtk_skip_values(c, count, FC_SCALAR_I32, err);
}

static fc_code vtk_data_section(fc_cursor *c, vtk_file *f, vtk_section section, fc_span rest, fc_error *err)
{
    fc_code code = vtk_arg_count(c, &rest, "tuple count", &f->tuples, err);
    if (code != FC_OK)
        return code;
    if (section == VTK_POINT_DATA) {
        if (!f->have_points)
            return fc_cursor_fail(c, err, "POINT_DATA before POINTS");
        if (f->tuples != f->point_count)
            return fc_cursor_fail(c, err, "POINT_DATA %llu does not match POINTS %llu",
                                  (unsigned long long)f->tuples, (unsigned long long)f->point_count);
    }
    f->section = section;
    return FC_OK;
}

static fc_code vtk_require_data_section(const fc_cursor *c, const vtk_file *f, const char *keyword, fc_error *err)
{
    if (f->section == VTK_DATASET)
        return fc_cursor_fail(c, err, "%s outside POINT_DATA or CELL_DATA", keyword);
    return FC_OK;
}

/* SCALARS name type [components], then an optional LOOKUP_TABLE name line. */
static fc_code vtk_scalars(fc_cursor *c, vtk_file *f, fc_span rest, fc_error *err)
{
    fc_span name, components_token;
    uint64_t components = 1;
    fc_scalar_type type = FC_SCALAR_F32;
    fc_code code = vtk_require_data_section(c, f, "SCALARS", err);
    if (code == FC_OK)
        code = vtk_arg(c, &rest, "array name", &name, err);
    if (code == FC_OK)
        code = vtk_arg_type(c, &rest, &type, err);
    if (code != FC_OK)
        return code;
    if (fc_span_next_token(&rest, &components_token) && !fc_span_to_count(components_token, &components))
        return fc_cursor_fail(c, err, "SCALARS component count is not a non-negative integer");
    if (fc_cursor_peek_keyword(c, "LOOKUP_TABLE")) {
        fc_span table_line;
        (void)fc_cursor_next_nonblank_line(c, &table_line); /* present: the peek just saw it */
    }
    return vtk_attribute_array(c, f, name, components, f->tuples, type, true, err);
}

/* VECTORS, NORMALS, TEXTURE_COORDINATES, TENSORS, GLOBAL_IDS, PEDIGREE_IDS:
 * `name type` with a fixed component count (texture coordinates: `name dim type`). */
static fc_code vtk_fixed_array(fc_cursor *c, vtk_file *f, fc_span keyword, fc_span rest, fc_error *err)
{
    fc_span name;
    uint64_t components = 3;
    fc_scalar_type type = FC_SCALAR_F32;
    char quoted[FC_QUOTE_MAX];
    fc_code code = vtk_require_data_section(c, f, fc_span_quote(keyword, quoted, sizeof quoted), err);
    if (code == FC_OK)
        code = vtk_arg(c, &rest, "array name", &name, err);
    if (code == FC_OK && fc_span_iequals(keyword, "TEXTURE_COORDINATES"))
        code = vtk_arg_count(c, &rest, "texture dimension", &components, err);
    if (code == FC_OK)
        code = vtk_arg_type(c, &rest, &type, err);
    if (code != FC_OK)
        return code;
    if (fc_span_iequals(keyword, "TENSORS"))
        components = 9;
    else if (fc_span_iequals(keyword, "TENSORS6"))
        components = 6;
    else if (fc_span_iequals(keyword, "GLOBAL_IDS") || fc_span_iequals(keyword, "PEDIGREE_IDS"))
        components = 1;
    bool is_vectors = fc_span_iequals(keyword, "VECTORS");
    return vtk_attribute_array(c, f, name, components, f->tuples, type, is_vectors, err);
}

/* COLOR_SCALARS name n and LOOKUP_TABLE name size: bytes in BINARY files,
 * floats in ASCII ones; never particle data. */
static fc_code vtk_color_array(fc_cursor *c, vtk_file *f, bool is_lookup_table, fc_span rest, fc_error *err)
{
    fc_span name;
    uint64_t count = 0;
    fc_code code = vtk_require_data_section(c, f, is_lookup_table ? "LOOKUP_TABLE" : "COLOR_SCALARS", err);
    if (code == FC_OK)
        code = vtk_arg(c, &rest, "name", &name, err);
    if (code == FC_OK)
        code = vtk_arg_count(c, &rest, is_lookup_table ? "table size" : "component count", &count, err);
    if (code != FC_OK)
        return code;
    fc_scalar_type type = c->binary ? FC_SCALAR_U8 : FC_SCALAR_F32;
    uint64_t tuples = is_lookup_table ? count : f->tuples;
    uint64_t components = is_lookup_table ? 4 : count;
    return vtk_array_data(c, tuples, components, type, NULL, err);
}

/* A METADATA block (VTK 8+): after its keyword line, text lines up to the next blank one. */
static void vtk_skip_metadata(fc_cursor *c)
{
    fc_span line;
    while (fc_cursor_next_line(c, &line) && !fc_span_is_blank(line)) {
    }
}

static fc_code vtk_field_array(fc_cursor *c, vtk_file *f, fc_error *err)
{
    fc_span line, rest, name;
    uint64_t components = 0, tuples = 0;
    fc_scalar_type type = FC_SCALAR_F32;
    if (!fc_cursor_next_nonblank_line(c, &line))
        return fc_cursor_fail(c, err, "FIELD ends before all its arrays");
    rest = line;
    fc_code code = vtk_arg(c, &rest, "array name", &name, err);
    if (code != FC_OK || fc_span_iequals(name, "NULL_ARRAY"))
        return code;
    code = vtk_arg_count(c, &rest, "component count", &components, err);
    if (code == FC_OK)
        code = vtk_arg_count(c, &rest, "tuple count", &tuples, err);
    if (code == FC_OK)
        code = vtk_arg_type(c, &rest, &type, err);
    if (code == FC_OK)
        code = vtk_attribute_array(c, f, name, components, tuples, type, true, err);
    if (code == FC_OK && fc_cursor_peek_keyword(c, "METADATA")) {
        (void)fc_cursor_next_nonblank_line(c, &line); /* the keyword line: the peek just saw it */
        vtk_skip_metadata(c);
    }
    return code;
}

static fc_code vtk_field(fc_cursor *c, vtk_file *f, fc_span rest, fc_error *err)
{
    fc_span name;
    uint64_t arrays = 0;
    fc_code code = vtk_arg(c, &rest, "field name", &name, err);
    if (code == FC_OK)
        code = vtk_arg_count(c, &rest, "array count", &arrays, err);
    for (uint64_t i = 0; code == FC_OK && i < arrays; i++)
        code = vtk_field_array(c, f, err);
    return code;
}

static fc_code vtk_section_line(fc_cursor *c, vtk_file *f, fc_span line, fc_error *err)
{
    static const char *const cell_keywords[] = { "CELLS", "VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS", NULL };
    static const char *const fixed_keywords[] = { "VECTORS", "NORMALS", "TEXTURE_COORDINATES", "TENSORS",
                                                  "TENSORS6", "GLOBAL_IDS", "PEDIGREE_IDS", NULL };
    fc_span rest = line, keyword;
    (void)fc_span_next_token(&rest, &keyword); /* present: the line is not blank */
    if (fc_span_iequals(keyword, "POINTS"))
        return vtk_points(c, f, rest, err);
    if (vtk_is_one_of(keyword, cell_keywords))
        return vtk_cells(c, rest, err);
    if (fc_span_iequals(keyword, "CELL_TYPES"))
        return vtk_cell_types(c, rest, err);
    if (fc_span_iequals(keyword, "POINT_DATA"))
        return vtk_data_section(c, f, VTK_POINT_DATA, rest, err);
    if (fc_span_iequals(keyword, "CELL_DATA"))
        return vtk_data_section(c, f, VTK_CELL_DATA, rest, err);
    if (fc_span_iequals(keyword, "SCALARS"))
        return vtk_scalars(c, f, rest, err);
    if (vtk_is_one_of(keyword, fixed_keywords))
        return vtk_fixed_array(c, f, keyword, rest, err);
    if (fc_span_iequals(keyword, "COLOR_SCALARS") || fc_span_iequals(keyword, "LOOKUP_TABLE"))
        return vtk_color_array(c, f, fc_span_iequals(keyword, "LOOKUP_TABLE"), rest, err);
    if (fc_span_iequals(keyword, "FIELD"))
        return vtk_field(c, f, rest, err);
    if (fc_span_iequals(keyword, "METADATA")) {
        vtk_skip_metadata(c);
        return FC_OK;
    }
    char quoted[FC_QUOTE_MAX];
    return fc_cursor_fail(c, err, "unknown keyword '%s'", fc_span_quote(keyword, quoted, sizeof quoted));
}

/* ---- header and scan ---- */

static fc_code vtk_header(fc_cursor *c, bool *binary, fc_error *err)
{
    fc_span line, rest, token;
    if (!fc_cursor_next_line(c, &line) || !fc_span_istarts_with(line, "# vtk DataFile Version"))
        return fc_cursor_fail(c, err, "not a legacy VTK file (no '# vtk DataFile Version' line)");
    if (!fc_cursor_next_line(c, &line) || !fc_cursor_next_line(c, &line))
        return fc_cursor_fail(c, err, "header ends before the ASCII/BINARY line");
    line = fc_span_trim(line);
    *binary = fc_span_iequals(line, "BINARY");
    if (!*binary && !fc_span_iequals(line, "ASCII"))
        return fc_cursor_fail(c, err, "expected ASCII or BINARY");
    if (!fc_cursor_next_nonblank_line(c, &line))
        return fc_cursor_fail(c, err, "missing DATASET line");
    rest = line;
    if (!fc_span_next_token(&rest, &token) || !fc_span_iequals(token, "DATASET") ||
        !fc_span_next_token(&rest, &token))
        return fc_cursor_fail(c, err, "expected DATASET POLYDATA or DATASET UNSTRUCTURED_GRID");
    if (!fc_span_iequals(token, "POLYDATA") && !fc_span_iequals(token, "UNSTRUCTURED_GRID")) {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "DATASET %s is not supported (POLYDATA or UNSTRUCTURED_GRID)",
                              fc_span_quote(token, quoted, sizeof quoted));
    }
    return FC_OK;
}

static fc_code vtk_scan(fc_cursor *c, vtk_file *f, fc_error *err)
{
    bool binary = false;
    fc_code code = vtk_header(c, &binary, err);
    if (code != FC_OK)
        return code;
    c->binary = binary; /* from here on errors report byte offsets */
    fc_span line;
    while (fc_cursor_next_nonblank_line(c, &line)) {
        code = vtk_section_line(c, f, line, err);
        if (code != FC_OK)
            return code;
    }
    if (!f->have_points)
        return fc_cursor_fail(c, err, "no POINTS section");
    return FC_OK;
}

/* ---- reading the particle arrays ---- */

static fc_code vtk_read_value(fc_cursor *c, const vtk_block *b, double *value, fc_error *err)
{
    if (c->binary) {
        if (!fc_cursor_read_scalar(c, b->type, true, value))
            return fc_cursor_fail(c, err, "unexpected end of data");
        return FC_OK;
    }
    fc_span token;
    if (!fc_cursor_next_token(c, &token))
        return fc_cursor_fail(c, err, "unexpected end of data");
    if (!fc_span_to_double(token, value)) {
        char quoted[FC_QUOTE_MAX];
        return fc_cursor_fail(c, err, "'%s' is not a number", fc_span_quote(token, quoted, sizeof quoted));
    }
    return FC_OK;
}

static fc_code vtk_read_block(const vtk_block *b, fc_frame *frame, fc_error *err)
{
    fc_cursor c = b->at;
    for (uint64_t i = 0; i < frame->count; i++) {
        for (uint64_t k = 0; k < b->components; k++) {
            size_t value_offset = c.pos;
            double value = 0.0;
            fc_field field = (fc_field)(b->first_field + (int)k);
            fc_code code = vtk_read_value(&c, b, &value, err);
            if (code != FC_OK)
                return code;
            bool stored = b->type == FC_SCALAR_F64 ? fc_field_store_position64(&c, frame, i, field, value)
                                                   : fc_field_store(frame, i, field, value);
            if (!stored) {
                if (c.binary)
                    c.pos = value_offset;
                return fc_field_reject(&c, err, i, field, value);
            }
        }
    }
    return FC_OK;
}

/* The other point arrays, as named scalars for --select (values that are no number stay NaN). */
static fc_code vtk_read_extras(const fc_cursor *c, const vtk_file *f, uint64_t count, fc_error *err)
{
    for (size_t k = 0; k < f->extra_count; k++) {
        fc_code code = FC_OK;
        double *values = fc_extras_add(c->extras, f->extra_names[k], count, c->name, err, &code);
        if (code != FC_OK)
            return code;
        fc_cursor at = f->extras[k].at;
        for (uint64_t i = 0; values != NULL && i < count; i++) {
            code = vtk_read_value(&at, &f->extras[k], &values[i], err);
            if (code != FC_OK)
                return code;
        }
    }
    return FC_OK;
}

static void vtk_init_blocks(vtk_file *f)
{
    *f = (vtk_file){ .section = VTK_DATASET };
    f->positions = (vtk_block){ .components = 3, .first_field = FC_FIELD_X };
    f->density = (vtk_block){ .components = 1, .first_field = FC_FIELD_DENSITY };
    f->velocity = (vtk_block){ .components = 3, .first_field = FC_FIELD_VX };
    f->ids = (vtk_block){ .components = 1, .first_field = FC_FIELD_ID };
    f->radius = (vtk_block){ .components = 1, .first_field = FC_FIELD_RADIUS };
}

fc_code fc_read_vtk(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    vtk_file f;
    vtk_init_blocks(&f);
    fc_code code = vtk_scan(c, &f, err);
    if (code != FC_OK)
        return code;
    uint32_t attributes = (f.density.present ? FC_ATTR_DENSITY : 0u) | (f.velocity.present ? FC_ATTR_VELOCITY : 0u) |
                          (f.ids.present ? FC_ATTR_IDS : 0u) | (f.radius.present ? FC_ATTR_RADIUS : 0u);
    code = fc_reader_alloc_frame(c, frame, f.point_count, attributes, err);
    const vtk_block *blocks[] = { &f.positions, &f.density, &f.velocity, &f.ids, &f.radius };
    for (size_t i = 0; code == FC_OK && i < sizeof blocks / sizeof blocks[0]; i++) {
        if (blocks[i]->present)
            code = vtk_read_block(blocks[i], frame, err);
    }
    if (code == FC_OK && c->extras != NULL)
        code = vtk_read_extras(c, &f, frame->count, err);
    return code;
}
