/* test_file.c — fc_read_file: whole files with their NUL, the size limit at
 * and one past it, files whose size stat does not tell (/proc), and the
 * errors, each naming the file. */
#define _POSIX_C_SOURCE 200809L   /* mkdtemp */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_file.h"
#include "test_util.h"

static char dir[] = "/tmp/fc_file_XXXXXX";

static const char *write_file(const char *name, const void *bytes, size_t size)
{
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    CHECK_MSG(f && fwrite(bytes, 1, size, f) == size, "cannot write %s", path);
    if (f)
        fclose(f);
    return path;
}

static void test_whole_file(void)
{
    const char *path = write_file("text", "one\ntwo\n", 8);
    uint8_t *data = NULL;
    size_t size = 0;
    fc_error err;
    CHECK_CODE(fc_read_file(path, SIZE_MAX, &data, &size, &err), FC_OK);
    CHECK(size == 8 && data && memcmp(data, "one\ntwo\n", 9) == 0);   /* the NUL after the end */
    free(data);

    path = write_file("empty", "", 0);
    CHECK_CODE(fc_read_file(path, 0, &data, &size, &err), FC_OK);
    CHECK(size == 0 && data && data[0] == '\0');
    free(data);
}

static void test_limit(void)
{
    static uint8_t bytes[200000];
    for (size_t i = 0; i < sizeof bytes; i++)
        bytes[i] = (uint8_t)(i * 7);
    const char *path = write_file("big", bytes, sizeof bytes);
    uint8_t *data = NULL;
    size_t size = 0;
    fc_error err;
    CHECK_CODE(fc_read_file(path, sizeof bytes, &data, &size, &err), FC_OK);
    CHECK(size == sizeof bytes && memcmp(data, bytes, size) == 0 && data[size] == 0);
    free(data);

    data = (uint8_t *)&size;   /* must be reset */
    CHECK_CODE(fc_read_file(path, sizeof bytes - 1, &data, &size, &err), FC_ERR_TOO_LARGE);
    CHECK(data == NULL && size == 0);
    char expected[256];
    snprintf(expected, sizeof expected, "%s: larger than %zu bytes", path, sizeof bytes - 1);
    CHECK_MSG(strcmp(err.message, expected) == 0, "%s", err.message);
}

/* /proc files report size 0: the buffer grows as they are read. */
static void test_unknown_size(void)
{
    uint8_t *data = NULL;
    size_t size = 0;
    fc_error err;
    CHECK_CODE(fc_read_file("/proc/self/status", SIZE_MAX, &data, &size, &err), FC_OK);
    CHECK(size > 0 && data && strlen((char *)data) == size && strstr((char *)data, "Name:") == (char *)data);
    free(data);
    CHECK_CODE(fc_read_file("/dev/null", 10, &data, &size, &err), FC_OK);
    CHECK(size == 0 && data && data[0] == '\0');
    free(data);
}

static void test_errors(void)
{
    uint8_t *data = NULL;
    size_t size = 0;
    fc_error err;
    char path[128], expected[256];
    snprintf(path, sizeof path, "%s/missing", dir);
    CHECK_CODE(fc_read_file(path, SIZE_MAX, &data, &size, &err), FC_ERR_IO);
    snprintf(expected, sizeof expected, "%s: cannot open: No such file or directory", path);
    CHECK_MSG(strcmp(err.message, expected) == 0, "%s", err.message);
    CHECK(data == NULL);

    CHECK_CODE(fc_read_file(dir, SIZE_MAX, &data, &size, &err), FC_ERR_IO);
    snprintf(expected, sizeof expected, "%s: not a regular file", dir);
    CHECK_MSG(strcmp(err.message, expected) == 0, "%s", err.message);
    CHECK(data == NULL);
}

int main(void)
{
    if (!mkdtemp(dir)) {
        CHECK_MSG(0, "cannot make a temporary folder");
        return test_result();
    }
    test_whole_file();
    test_limit();
    test_unknown_size();
    test_errors();
    const char *names[] = {"text", "empty", "big"};
    for (size_t i = 0; i < 3; i++) {
        char path[128];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        unlink(path);
    }
    rmdir(dir);
    return test_result();
}
