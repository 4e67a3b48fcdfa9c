/* test_e2e_bench.c — runs fluidcast-e2e-bench with tiny settings against the
 * real fluidcastd it starts, parses its markdown tables and checks what they
 * say against what was asked and against each other.
 * usage: test_e2e_bench BENCH FLUIDCASTD */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "test_util.h"

#define MAX_COLUMNS 16
#define MAX_ROWS 8
#define STREAM_SECONDS 1.5
#define FIXED_PUSH_FPS 40

typedef struct table {
    char header[MAX_COLUMNS][32];
    char cells[MAX_ROWS][MAX_COLUMNS][48];
    int columns, rows;
} table;

static char *run_capture(const char *command, int *status)
{
    FILE *p = popen(command, "r");
    size_t size = 0, capacity = 1 << 16;
    char *out = malloc(capacity);
    if (!p || !out) {
        free(out);
        return NULL;
    }
    size_t n;
    while ((n = fread(out + size, 1, capacity - size - 1, p)) > 0)
        if ((size += n) == capacity - 1 && !(out = realloc(out, capacity *= 2)))
            break;
    int rc = pclose(p);
    *status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    if (out)
        out[size] = '\0';
    return out;
}

/* Cells of one "| a | b |" line, trimmed; the number of cells. */
static int split_row(const char *line, char cells[MAX_COLUMNS][48])
{
    int n = 0;
    const char *p = strchr(line, '|');
    while (p && n < MAX_COLUMNS) {
        const char *end = strchr(p + 1, '|');
        const char *eol = strchr(p + 1, '\n');
        if (!end || (eol && eol < end))
            break;
        const char *a = p + 1, *b = end;
        while (a < b && *a == ' ')
            a++;
        while (b > a && b[-1] == ' ')
            b--;
        snprintf(cells[n++], 48, "%.*s", (int)(b - a), a);
        p = end;
    }
    return n;
}

/* The table under heading `section` ("## ..."): header, separator, rows up to a blank line. */
static int parse_table(const char *text, const char *section, table *t)
{
    memset(t, 0, sizeof *t);
    const char *at = strstr(text, section);
    if (!at || !(at = strstr(at, "\n| ")))
        return 0;
    at++;
    char header[MAX_COLUMNS][48];
    t->columns = split_row(at, header);
    for (int c = 0; c < t->columns; c++)
        snprintf(t->header[c], sizeof t->header[c], "%s", header[c]);
    at = strchr(at, '\n');
    if (!at || strncmp(at + 1, "|---", 4) != 0)
        return 0;
    at = strchr(at + 1, '\n');
    while (at && at[1] == '|' && t->rows < MAX_ROWS) {
        if (split_row(at + 1, t->cells[t->rows]) != t->columns)
            return 0;
        t->rows++;
        at = strchr(at + 1, '\n');
    }
    return t->rows > 0;
}

static double cell(const table *t, int row, const char *column)
{
    for (int c = 0; c < t->columns; c++)
        if (strcmp(t->header[c], column) == 0) {
            char *end;
            double v = strtod(t->cells[row][c], &end);
            return end != t->cells[row][c] && *end == '\0' ? v : NAN;
        }
    return NAN;
}

static const char *text_cell(const table *t, int row, const char *column)
{
    for (int c = 0; c < t->columns; c++)
        if (strcmp(t->header[c], column) == 0)
            return t->cells[row][c];
    return "";
}

static void check_config(const table *t, int row, const char *format)
{
    CHECK_MSG(cell(t, row, "particles") == 2048, "row %d particles %s", row, text_cell(t, row, "particles"));
    CHECK_MSG(strcmp(text_cell(t, row, "size"), "64x48") == 0, "row %d size %s", row, text_cell(t, row, "size"));
    CHECK_MSG(strcmp(text_cell(t, row, "format"), format) == 0, "row %d format %s", row,
              text_cell(t, row, "format"));
}

static void check_requests(const char *out)
{
    table t;
    CHECK_MSG(parse_table(out, "## Request/response", &t) && t.rows == 2, "request table: %d rows", t.rows);
    for (int r = 0; r < t.rows; r++) {
        check_config(&t, r, r == 0 ? "jpeg" : "png");
        CHECK_MSG(cell(&t, r, "requests") == 3, "row %d: %g of 3 requests answered", r, cell(&t, r, "requests"));
        double median = cell(&t, r, "median ms"), p99 = cell(&t, r, "p99 ms"), mean = cell(&t, r, "mean ms");
        CHECK_MSG(median > 0 && p99 >= median && mean > 0, "row %d: median %g p99 %g mean %g", r, median, p99,
                  mean);
        /* With 3 samples the mean lies between the smallest and the maximum (= p99). */
        CHECK_MSG(mean <= p99 + 0.05, "row %d: mean %g above the maximum %g", r, mean, p99);
        /* The table rounds the mean to 0.01 ms and fps to 0.01. */
        CHECK_NEAR(cell(&t, r, "fps"), 1000.0 / mean, 1000.0 / (mean - 0.005) - 1000.0 / mean + 0.005);
        CHECK(cell(&t, r, "image KiB") > 0);
    }
    table s;
    CHECK_MSG(parse_table(out, "## Server stages per request", &s) && s.rows == 2, "stage table: %d rows", s.rows);
    for (int r = 0; r < s.rows; r++) {
        check_config(&s, r, r == 0 ? "jpeg" : "png");
        double total = cell(&s, r, "server total"), encode = cell(&s, r, "encode"), depth = cell(&s, r, "depth");
        CHECK_MSG(total > 0 && encode > 0 && depth > 0 && total >= encode + depth - 0.02,
                  "row %d: total %g encode %g depth %g", r, total, encode, depth);
        /* The server's part cannot exceed what the client waited for the whole request. */
        CHECK_MSG(total <= cell(&t, r, "mean ms") + 0.05, "row %d: server total %g > client mean %g", r, total,
                  cell(&t, r, "mean ms"));
    }
}

static void check_stream_row(const table *t, int r, double expected_push_fps)
{
    double pushed = cell(t, r, "pushed"), received = cell(t, r, "received"), skipped = cell(t, r, "skipped");
    double in_flight = cell(t, r, "in flight"), push_fps = cell(t, r, "push fps");
    CHECK_MSG(pushed >= 1 && received >= 1 && received <= pushed, "row %d: pushed %g received %g", r, pushed,
              received);
    /* Protocol 10.7: images received plus their `missed` add up to the frames
     * published, and the end of the session delivers the last one first: nothing is
     * left in flight once the viewer was told the session ended. */
    CHECK_MSG(in_flight == 0 && received + skipped == pushed, "row %d: pushed %g received %g skipped %g in flight %g",
              r, pushed, received, skipped, in_flight);
    /* The producer pushed for at least STREAM_SECONDS (how much longer its last
     * send takes depends on the machine's load); push fps is rounded to 0.1. */
    double push_seconds = pushed / push_fps;
    CHECK_MSG(push_seconds >= STREAM_SECONDS * (1 - 0.05 / push_fps), "row %d: %g frames at %g fps", r, pushed,
              push_fps);
    /* At a fixed rate, never faster than asked (the frames due within STREAM_SECONDS);
     * slower on a loaded machine is no failure of the pacing. */
    if (expected_push_fps > 0)
        CHECK_MSG(push_fps <= expected_push_fps + 0.1, "row %d: push fps %g, asked %g", r, push_fps,
                  expected_push_fps);
    /* The viewer's images span at least the push time. */
    double fps = cell(t, r, "viewer fps");
    CHECK_MSG(fps > 0 && fps <= received / STREAM_SECONDS + 0.01, "row %d: viewer fps %g for %g images", r, fps,
              received);
    double median = cell(t, r, "median ms"), p99 = cell(t, r, "p99 ms");
    CHECK_MSG(median > 0 && p99 >= median, "row %d: median %g p99 %g", r, median, p99);
}

static void check_header(const char *out)
{
    CHECK_MSG(strstr(out, "- renderer: llvmpipe") != NULL, "no llvmpipe renderer line");
    CHECK(strstr(out, "- load average before: ") != NULL);
    CHECK(strstr(out, "- load average after: ") != NULL);
    CHECK(strstr(out, "- command: `") != NULL);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s FLUIDCAST_E2E_BENCH FLUIDCASTD\n", argv[0]);
        return 2;
    }
    char command[2048];
    int status;

    snprintf(command, sizeof command,
             "%s --daemon %s --particles 2k --size 64x48 --format jpeg,png --requests 3 --stream-seconds %g",
             argv[1], argv[2], STREAM_SECONDS);
    char *out = run_capture(command, &status);
    CHECK_MSG(out && status == 0, "'%s' exited with %d", command, status);
    if (out) {
        check_header(out);
        check_requests(out);
        table t;
        CHECK_MSG(parse_table(out, "## Streaming", &t) && t.rows == 2, "stream table: %d rows", t.rows);
        for (int r = 0; r < t.rows; r++) {
            check_config(&t, r, r == 0 ? "jpeg" : "png");
            check_stream_row(&t, r, 0);
        }
    }
    free(out);

    snprintf(command, sizeof command,
             "%s --daemon %s --particles 2k --size 64x48 --format jpeg --requests 0 --stream-seconds %g "
             "--push-fps %d --density",
             argv[1], argv[2], STREAM_SECONDS, FIXED_PUSH_FPS);
    out = run_capture(command, &status);
    CHECK_MSG(out && status == 0, "'%s' exited with %d", command, status);
    if (out) {
        table t;
        CHECK_MSG(strstr(out, "## Request/response") == NULL, "--requests 0 still printed requests");
        CHECK_MSG(parse_table(out, "## Streaming", &t) && t.rows == 1, "fixed-rate stream table: %d rows", t.rows);
        if (t.rows == 1)
            check_stream_row(&t, 0, FIXED_PUSH_FPS);
    }
    free(out);

    snprintf(command, sizeof command, "%s --size 0x48 2>/dev/null", argv[1]);
    out = run_capture(command, &status);
    CHECK_MSG(status == 2, "a bad --size exited with %d, expected 2 (usage)", status);
    free(out);
    return test_result();
}
