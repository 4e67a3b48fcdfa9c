/* reader_csv.c — comma-separated values with a header line naming the columns
 * (x y z required; density|rho, vx vy vz, id optional; others ignored).
 * Blank lines and lines starting with '#' are skipped everywhere. */
#include "reader_formats.h"

#include <stdlib.h>
#include <string.h>
#include "fc_error.h"
#include "reader_fields.h"

typedef struct csv_layout {
    fc_field *columns;   /* what each column provides; FC_FIELD_NONE for ignored ones */
    size_t column_count;
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

static size_t csv_count_fields(fc_span line)
{
    size_t count = 1;
    const char *p = line.ptr, *end = line.ptr + line.len;
    while ((p = memchr(p, ',', (size_t)(end - p))) != NULL) {
        count++;
        p++;
    }
    return count;
}

static fc_code csv_parse_header(const fc_cursor *c, fc_span line, csv_layout *l, fc_error *err)
{
    l->column_count = csv_count_fields(line);
    l->columns = calloc(l->column_count, sizeof *l->columns);
    if (l->columns == NULL)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory for %zu columns", c->name, l->column_count);
    fc_span rest = line, name;
    for (size_t i = 0; fc_span_next_field(&rest, ',', &name); i++) {
        name = fc_span_trim(name);
        l->columns[i] = fc_field_from_name(name);
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
    size_t found = csv_count_fields(line);
    if (found != l->column_count)
        return fc_cursor_fail(c, err, "expected %zu values, found %zu", l->column_count, found);
    fc_span rest = line, text;
    for (size_t i = 0; fc_span_next_field(&rest, ',', &text); i++) {
        fc_field field = l->columns[i];
        double value = 0.0;
        if (field == FC_FIELD_NONE)
            continue;
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

static fc_code csv_read_records(fc_cursor *c, const csv_layout *l, fc_frame *frame, fc_error *err)
{
    fc_code code = fc_reader_alloc_frame(c, frame, csv_count_records(*c), l->attributes, err);
    fc_span line;
    for (uint64_t index = 0; code == FC_OK && csv_next_record(c, &line); index++)
        code = csv_read_record(c, line, l, index, frame, err);
    return code;
}

fc_code fc_read_csv(fc_cursor *c, fc_frame *frame, fc_error *err)
{
    static const uint8_t utf8_bom[3] = { 0xEF, 0xBB, 0xBF };
    if (c->size >= sizeof utf8_bom && memcmp(c->data, utf8_bom, sizeof utf8_bom) == 0)
        c->pos = sizeof utf8_bom; /* spreadsheets write one */
    fc_span line;
    if (!csv_next_record(c, &line))
        return fc_cursor_fail(c, err, "no header line");
    csv_layout layout = { NULL, 0, { { false } }, 0 };
    fc_code code = csv_parse_header(c, line, &layout, err);
    if (code == FC_OK)
        code = csv_read_records(c, &layout, frame, err);
    free(layout.columns);
    return code;
}
