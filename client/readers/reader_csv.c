/* reader_csv.c — comma-separated values with a header line naming the columns
 * (x y z required; density|rho, vx vy vz, id optional; others ignored).
 * Blank lines and lines starting with '#' are skipped everywhere.
 *
 * DualSPHysics' CSV (PartVTK -savecsv) is read too: ';' separates the values
 * (chosen when the header has ';' and no ','), names carry their units in
 * brackets ("Pos.x [m]", "Rhop [kg/m^3]"), each line ends with a ';', a short
 * preamble ("TimeStep [s];Np;..." and its values) may come before the header,
 * and a line of units may follow it. */
#include "reader_formats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_extras.h"
#include "reader_fields.h"

enum { CSV_MAX_PREAMBLE = 8 };

typedef struct csv_layout {
    char separator;
    fc_field *columns;   /* what each column provides; FC_FIELD_NONE for ignored ones */
    size_t column_count;
    fc_span *names;      /* each column's name without its unit */
    double **extras;     /* per column: where its values go for --select (c->extras), or NULL */
    fc_field_set fields;
    uint32_t attributes; /* fc_frame_alloc mask for the fields present */
} csv_layout;

static bool csv_is_record(fc_span line)
{
    fc_span trimmed = fc_span_trim(line);
    return trimmed.len > 0 && trimmed.ptr[0] != '#';
}

static bool csv_next_record(fc_cursor *c, fc_span *line)
{
    while (fc_cursor_next_line(c, line)) {
        if (csv_is_record(*line))
            return true;
    }
    return false;
}

/* The line without the separator DualSPHysics ends every line with. */
static fc_span csv_strip_trailing(fc_span line, char separator)
{
    line = fc_span_trim(line);
    if (line.len > 0 && line.ptr[line.len - 1] == separator)
        line.len--;
    return line;
}

static size_t csv_count_fields(fc_span line, char separator)
{
    size_t count = 1;
    const char *p = line.ptr, *end = line.ptr + line.len;
    while ((p = memchr(p, separator, (size_t)(end - p))) != NULL) {
        count++;
        p++;
    }
    return count;
}

static char csv_separator(fc_span header)
{
    bool semicolon = memchr(header.ptr, ';', header.len) != NULL;
    return semicolon && memchr(header.ptr, ',', header.len) == NULL ? ';' : ',';
}

/* A column's name without its unit: "Pos.x [m]" -> "Pos.x". */
static fc_span csv_strip_unit(fc_span name)
{
    name = fc_span_trim(name);
    if (name.len > 0 && name.ptr[name.len - 1] == ']') {
        for (size_t i = name.len - 1; i-- > 0;) {
            if (name.ptr[i] == '[') {
                name.len = i;
                break;
            }
        }
    }
    return fc_span_trim(name);
}

/* The field a column gives: the common names, then DualSPHysics' (Pos.x Vel.x Rhop Idp). */
static fc_field csv_field_from_name(fc_span name)
{
    static const struct {
        const char *name;
        fc_field field;
    } dualsphysics[] = {
        { "pos.x", FC_FIELD_X },  { "pos.y", FC_FIELD_Y },  { "pos.z", FC_FIELD_Z },       { "vel.x", FC_FIELD_VX },
        { "vel.y", FC_FIELD_VY }, { "vel.z", FC_FIELD_VZ }, { "rhop", FC_FIELD_DENSITY }, { "idp", FC_FIELD_ID },
    };
    name = csv_strip_unit(name);
    fc_field field = fc_field_from_name(name);
    for (size_t i = 0; field == FC_FIELD_NONE && i < sizeof dualsphysics / sizeof dualsphysics[0]; i++) {
        if (fc_span_iequals(name, dualsphysics[i].name))
            field = dualsphysics[i].field;
    }
    return field;
}

/* Whether a line names the x, y and z columns: what tells a header from a preamble. */
static bool csv_names_positions(fc_span line, char separator)
{
    bool axes[3] = { false, false, false };
    fc_span rest = csv_strip_trailing(line, separator), name;
    while (fc_span_next_field(&rest, separator, &name)) {
        fc_field field = csv_field_from_name(name);
        if (field >= FC_FIELD_X && field <= FC_FIELD_Z)
            axes[field - FC_FIELD_X] = true;
    }
    return axes[0] && axes[1] && axes[2];
}

/* A line under the header none of whose values is a number: the units. */
static bool csv_is_units_line(fc_span line, char separator)
{
    fc_span rest = csv_strip_trailing(line, separator), text;
    while (fc_span_next_field(&rest, separator, &text)) {
        double value;
        if (fc_span_to_double(fc_span_trim(text), &value))
            return false;
    }
    return true;
}

static fc_code csv_parse_header(const fc_cursor *c, fc_span line, csv_layout *l, fc_error *err)
{
    line = csv_strip_trailing(line, l->separator);
    l->column_count = csv_count_fields(line, l->separator);
    l->columns = calloc(l->column_count, sizeof *l->columns);
    l->names = calloc(l->column_count, sizeof *l->names);
    l->extras = calloc(l->column_count, sizeof *l->extras);
    if (l->columns == NULL || l->names == NULL || l->extras == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory for %zu columns", c->name, l->column_count);
    fc_span rest = line, name;
    for (size_t i = 0; fc_span_next_field(&rest, l->separator, &name); i++) {
        name = fc_span_trim(name);
        l->names[i] = csv_strip_unit(name);
        l->columns[i] = csv_field_from_name(name);
        if (l->columns[i] != FC_FIELD_NONE && !fc_field_set_add(&l->fields, l->columns[i])) {
            char quoted[FC_QUOTE_MAX];
            return fc_cursor_fail(c, err, "column '%s' gives %s a second time",
                                  fc_span_quote(name, quoted, sizeof quoted), fc_field_name(l->columns[i]));
        }
    }
    const char *missing = NULL;
    if (!fc_field_set_attributes(&l->fields, &l->attributes, &missing))
        return fc_cursor_fail(c, err, "header: %s", missing);
    return FC_OK;
}

static uint64_t csv_count_records(fc_cursor c)
{
    uint64_t count = 0;
    fc_span line;
    while (csv_next_record(&c, &line))
        count++;
    return count;
}

static fc_code csv_read_record(const fc_cursor *c, fc_span line, const csv_layout *l, uint64_t index,
                               fc_frame *frame, fc_error *err)
{
    line = csv_strip_trailing(line, l->separator);
    size_t found = csv_count_fields(line, l->separator);
    if (found != l->column_count)
        return fc_cursor_fail(c, err, "expected %zu values, found %zu", l->column_count, found);
    fc_span rest = line, text;
    for (size_t i = 0; fc_span_next_field(&rest, l->separator, &text); i++) {
        fc_field field = l->columns[i];
        double value = 0.0;
        if (field == FC_FIELD_NONE) {
            if (l->extras[i] != NULL && !fc_span_to_double(fc_span_trim(text), &l->extras[i][index]))
                l->extras[i][index] = NAN; /* only a selection reads it; text matches no value */
            continue;
        }
        text = fc_span_trim(text);
        if (!fc_span_to_double(text, &value)) {
            char quoted[FC_QUOTE_MAX];
            return fc_cursor_fail(c, err, "column %zu (%s): '%s' is not a number", i + 1, fc_field_name(field),
                                  fc_span_quote(text, quoted, sizeof quoted));
        }
        if (!fc_field_store(frame, index, field, value))
            return fc_field_reject(c, err, index, field, value);
    }
    return FC_OK;
}

/* The columns no attribute takes, kept by name for --select when the read asks for them. */
static fc_code csv_keep_extras(const fc_cursor *c, const csv_layout *l, uint64_t count, fc_error *err)
{
    for (size_t i = 0; c->extras != NULL && i < l->column_count; i++) {
        fc_code code = FC_OK;
        if (l->columns[i] == FC_FIELD_NONE)
            l->extras[i] = fc_extras_add(c->extras, l->names[i], count, c->name, err, &code);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

static fc_code csv_read_records(fc_cursor *c, const csv_layout *l, fc_frame *frame, fc_error *err)
{
    uint64_t count = csv_count_records(*c);
    fc_code code = fc_reader_alloc_frame(c, frame, count, l->attributes, err);
    if (code == FC_OK)
        code = csv_keep_extras(c, l, count, err);
    fc_span line;
    for (uint64_t index = 0; code == FC_OK && csv_next_record(c, &line); index++)
        code = csv_read_record(c, line, l, index, frame, err);
    return code;
}

/* DualSPHysics puts a line of totals and its values before the header: when the first line does not name
 * x, y and z, the header is the first of the next few lines that does (else the first line stays the header
 * and its error says what it lacks). */
static void csv_skip_preamble(fc_cursor *c, fc_span *header)
{
    if (csv_names_positions(*header, ';'))
        return;
    fc_cursor ahead = *c;
    fc_span line;
    for (int i = 0; i < CSV_MAX_PREAMBLE && csv_next_record(&ahead, &line); i++) {
        if (csv_names_positions(line, ';')) {
            *c = ahead;
            *header = line;
            return;
        }
    }
}

static void csv_skip_units_line(fc_cursor *c, char separator)
{
    fc_cursor ahead = *c;
    fc_span line;
    if (csv_next_record(&ahead, &line) && csv_is_units_line(line, separator))
        *c = ahead;
}

fc_code fc_read_csv(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    static const uint8_t utf8_bom[3] = { 0xEF, 0xBB, 0xBF };
    if (c->size >= sizeof utf8_bom && memcmp(c->data, utf8_bom, sizeof utf8_bom) == 0)
        c->pos = sizeof utf8_bom; /* spreadsheets write one */
    fc_span line;
    if (!csv_next_record(c, &line))
        return fc_cursor_fail(c, err, "no header line");
    csv_layout layout = { csv_separator(line), NULL, 0, NULL, NULL, { { false } }, 0 };
    if (layout.separator == ';')
        csv_skip_preamble(c, &line);
    fc_code code = csv_parse_header(c, line, &layout, err);
    if (code == FC_OK)
        csv_skip_units_line(c, layout.separator);
    if (code == FC_OK)
        code = csv_read_records(c, &layout, frame, err);
    free(layout.columns);
    free(layout.names);
    free(layout.extras);
    return code;
}
