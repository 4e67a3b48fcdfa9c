/* test_msg_types.c — the message types: every one wire.h defines has its name,
 * and the message table of PROTOCOL.md (section 7, the normative spec) lists
 * exactly these types, with these numbers and names. The table is read from
 * the markdown itself, so the spec and the code cannot drift apart.
 *
 * Usage: test_msg_types PATH/TO/PROTOCOL.md */
#include <ctype.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"
#include "wire.h"

#define MAX_ROWS 256
#define MAX_NAME 64
#define ROW_CELLS 2   /* the cells read of each row: type, name */

typedef struct spec_row {
    long type;
    char name[MAX_NAME];
} spec_row;

typedef struct spec_table {
    spec_row rows[MAX_ROWS];
    int count;
    int tables;     /* tables whose header starts "| type | name |": exactly one is expected */
    int bad_rows;   /* rows of it that do not read as a number and an upper-case name */
} spec_table;

/* Copies the next '|'-separated cell of *line (after the one at *line),
 * trimmed, into out; false at the end of the line. */
static bool next_cell(const char **line, char *out, size_t size)
{
    const char *p = *line;
    if (*p != '|')
        return false;
    p++;
    const char *end = strchr(p, '|');
    if (!end)
        return false;
    while (p < end && isspace((unsigned char)*p))
        p++;
    const char *last = end;
    while (last > p && isspace((unsigned char)last[-1]))
        last--;
    size_t len = (size_t)(last - p);
    if (len >= size)
        len = size - 1;
    memcpy(out, p, len);
    out[len] = '\0';
    *line = end;
    return true;
}

/* The first ROW_CELLS cells of a table line; false when it has fewer. */
static bool read_cells(const char *line, char cells[ROW_CELLS][MAX_NAME])
{
    for (int i = 0; i < ROW_CELLS; i++)
        if (!next_cell(&line, cells[i], MAX_NAME))
            return false;
    return true;
}

static bool is_type_name(const char *s)
{
    if (!*s)
        return false;
    for (; *s; s++)
        if (!(isupper((unsigned char)*s) || *s == '_'))
            return false;
    return true;
}

static void add_row(spec_table *t, char cells[ROW_CELLS][MAX_NAME])
{
    char *end;
    long type = strtol(cells[0], &end, 10);
    if (cells[0][0] == '\0' || *end != '\0' || type < 0 || type > UINT16_MAX || !is_type_name(cells[1]) ||
        t->count == MAX_ROWS) {
        t->bad_rows++;
        return;
    }
    t->rows[t->count].type = type;
    snprintf(t->rows[t->count].name, MAX_NAME, "%s", cells[1]);
    t->count++;
}

/* Reads every table of the markdown whose header row begins "| type | name |". */
static void parse_spec(const char *markdown, spec_table *t)
{
    memset(t, 0, sizeof *t);
    bool in_table = false, after_header = false;
    for (const char *line = markdown; *line;) {
        const char *eol = strchr(line, '\n');
        size_t len = eol ? (size_t)(eol - line) : strlen(line);
        char buf[512];
        snprintf(buf, sizeof buf, "%.*s", (int)(len < sizeof buf ? len : sizeof buf - 1), line);
        char cells[ROW_CELLS][MAX_NAME];
        bool is_row = buf[0] == '|' && read_cells(buf, cells);
        if (!is_row) {
            in_table = false;
        } else if (in_table && after_header) {
            after_header = false;   /* the |---| separator */
        } else if (in_table) {
            add_row(t, cells);
        } else if (strcmp(cells[0], "type") == 0 && strcmp(cells[1], "name") == 0) {
            in_table = after_header = true;
            t->tables++;
        }
        line += len + (eol ? 1 : 0);
    }
}

static const spec_row *spec_find(const spec_table *t, long type)
{
    for (int i = 0; i < t->count; i++)
        if (t->rows[i].type == type)
            return &t->rows[i];
    return NULL;
}

/* Counts one difference, and prints it when reporting. */
static void mismatch(int *bad, bool report, const char *fmt, ...)
{
    (*bad)++;
    if (!report)
        return;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "PROTOCOL.md vs wire.h: ");
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

/* Differences between the spec's table and the code; each is printed when `report`. */
static int spec_mismatches(const char *markdown, bool report)
{
    static spec_table t;
    parse_spec(markdown, &t);
    int bad = 0;
#define MISMATCH(...) mismatch(&bad, report, __VA_ARGS__)
    if (t.tables != 1)
        MISMATCH("%d tables with the header \"| type | name |\", expected the one of section 7", t.tables);
    if (t.bad_rows)
        MISMATCH("%d rows of the message table are not \"| number | NAME |\"", t.bad_rows);
    for (int i = 0; i < t.count; i++)
        for (int j = i + 1; j < t.count; j++)
            if (t.rows[i].type == t.rows[j].type || strcmp(t.rows[i].name, t.rows[j].name) == 0)
                MISMATCH("rows %s (%ld) and %s (%ld) repeat a number or a name", t.rows[i].name, t.rows[i].type,
                         t.rows[j].name, t.rows[j].type);
    /* Every number a name in the code stands for is in the spec under that name, and no other. */
    for (long type = 0; type <= UINT16_MAX; type++) {
        const char *name = fc_msg_name((uint16_t)type);
        const spec_row *row = spec_find(&t, type);
        if (name && !row)
            MISMATCH("type %ld (%s) is missing from the table", type, name);
        else if (!name && row)
            MISMATCH("the table lists type %ld (%s), which wire.h does not define", type, row->name);
        else if (name && strcmp(name, row->name) != 0)
            MISMATCH("type %ld is %s in wire.h but %s in the table", type, name, row->name);
    }
#undef MISMATCH
    return bad;
}

/* Every member of fc_msg_type (walked through the list it is made from) has
 * the name of its enumerator, and the names are distinct. */
static void test_every_type_has_its_name(void)
{
    static const struct {
        fc_msg_type type;
        const char *name;
    } all[] = {
#define ENTRY(name, number) {FC_MSG_##name, #name},
        FC_MSG_TYPES(ENTRY)
#undef ENTRY
    };
    size_t n = sizeof all / sizeof all[0];
    for (size_t i = 0; i < n; i++) {
        const char *name = fc_msg_name((uint16_t)all[i].type);
        CHECK_MSG(name && strcmp(name, all[i].name) == 0, "type %d is named %s, expected %s", (int)all[i].type,
                  name ? name : "(none)", all[i].name);
        for (size_t j = i + 1; j < n; j++)
            CHECK_MSG(all[i].type != all[j].type, "%s and %s share number %d", all[i].name, all[j].name,
                      (int)all[i].type);
    }
    /* The numbers the protocol leaves undefined have no name. */
    CHECK(fc_msg_name(0) == NULL);
    CHECK(fc_msg_name(14) == NULL && fc_msg_name(15) == NULL);
    CHECK(fc_msg_name(27) == NULL && fc_msg_name(UINT16_MAX) == NULL);
}

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long size = ftell(f);
        if (size >= 0 && fseek(f, 0, SEEK_SET) == 0 && (text = malloc((size_t)size + 1)) != NULL) {
            size_t got = fread(text, 1, (size_t)size, f);
            text[got] = '\0';
        }
    }
    fclose(f);
    return text;
}

/* A message table as PROTOCOL.md writes one, made from the code's list. */
static void table_from_code(char *out, size_t size)
{
    size_t len = (size_t)snprintf(out, size, "## 7. Messages\n\n| type | name | direction | payload |\n"
                                              "|------|------|-----------|---------|\n");
#define ROW(name, number)                                                                           \
    if (len < size)                                                                                 \
        len += (size_t)snprintf(out + len, size - len, "| %d | %s | either way | 7.1 |\n", number, #name);
    FC_MSG_TYPES(ROW)
#undef ROW
    if (len < size)
        snprintf(out + len, size - len, "\nText after the table.\n");
    CHECK_MSG(len < size, "the table made from the code needs more than %zu bytes", size);
}

/* The markdown with its first occurrence of `from` replaced by `to` (from must occur). */
static char *edited(const char *markdown, const char *from, const char *to)
{
    const char *at = strstr(markdown, from);
    CHECK_MSG(at != NULL, "\"%s\" is not in the table", from);
    if (!at)
        return NULL;
    size_t head = (size_t)(at - markdown), from_len = strlen(from), to_len = strlen(to);
    char *out = malloc(strlen(markdown) - from_len + to_len + 1);
    if (!out)
        return NULL;
    memcpy(out, markdown, head);
    memcpy(out + head, to, to_len);
    strcpy(out + head + to_len, at + from_len);
    return out;
}

static void check_edit_is_caught(const char *markdown, const char *from, const char *to)
{
    char *text = edited(markdown, from, to);
    if (!text)
        return;
    CHECK_MSG(spec_mismatches(text, false) > 0, "the check misses \"%s\" changed to \"%s\"", from, to);
    free(text);
}

/* The comparison itself catches each kind of drift, shown on a table made from the code. */
static void test_drift_is_caught(void)
{
    static char table[8192];
    table_from_code(table, sizeof table);
    CHECK_MSG(spec_mismatches(table, true) == 0, "the table made from the code does not match it:\n%s", table);
    check_edit_is_caught(table, "| 13 | MESH_TRANSFORM |", "| 14 | MESH_TRANSFORM |");          /* renumbered */
    check_edit_is_caught(table, "| 22 | FRAME_PACKED |", "| 22 | FRAME_PACKET |");              /* renamed */
    check_edit_is_caught(table, "| 24 | SESSION_LIST | either way | 7.1 |\n", "");              /* dropped */
    check_edit_is_caught(table, "| 9 | GOODBYE |", "| 15 | RESERVED | x | y |\n| 9 | GOODBYE |");    /* added */
    check_edit_is_caught(table, "| 5 | SETTINGS |", "| 5 | SETTINGS |\n| 5 | SETTINGS |");       /* repeated */
    check_edit_is_caught(table, "| 3 | FRAME |", "| three | FRAME |");                         /* unreadable */
    check_edit_is_caught(table, "| type | name |", "| kind | name |");                         /* table lost */
    /* a second table */
    check_edit_is_caught(table, "Text after", "| type | name |\n|---|---|\n| 1 | HELLO |\n\nText after");
}

static void test_spec_lists_exactly_these_types(const char *path)
{
    char *spec = read_file(path);
    CHECK_MSG(spec != NULL, "cannot read %s", path);
    if (!spec)
        return;
    CHECK_MSG(spec_mismatches(spec, true) == 0, "%s and wire.h's FC_MSG_TYPES differ (above)", path);
    free(spec);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s PROTOCOL.md\n", argv[0]);
        return 2;
    }
    test_every_type_has_its_name();
    test_drift_is_caught();
    test_spec_lists_exactly_these_types(argv[1]);
    return test_result();
}
