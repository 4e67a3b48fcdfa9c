/* log.c — timestamped, leveled log lines on stderr. */
#include "log.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "fc_error.h"

static const char *const level_names[] = {"error", "warn", "info", "debug"};

fc_code fc_log_level_parse(const char *text, fc_log_level *out, fc_error *err)
{
    for (int level = FC_LOG_ERROR; level <= FC_LOG_DEBUG; level++) {
        if (strcmp(text, level_names[level]) == 0) {
            *out = (fc_log_level)level;
            return FC_OK;
        }
    }
    return fc_error_set(err, FC_ERR_USAGE, "log level '%s' is not one of error, warn, info, debug", text);
}

const char *fc_log_level_name(fc_log_level level)
{
    return level >= FC_LOG_ERROR && level <= FC_LOG_DEBUG ? level_names[level] : "?";
}

/* UTC with milliseconds, so lines from several machines sort together. */
static void format_timestamp(char *out, size_t size)
{
    struct timespec now;
    struct tm utc;
    clock_gettime(CLOCK_REALTIME, &now);
    gmtime_r(&now.tv_sec, &utc);
    size_t n = strftime(out, size, "%Y-%m-%dT%H:%M:%S", &utc);
    snprintf(out + n, size - n, ".%03ldZ", now.tv_nsec / 1000000L);
}

void fc_log_write(const fc_log *log, fc_log_level level, const char *fmt, ...)
{
    if (level > log->level)
        return;
    char stamp[40];
    char message[1024];
    format_timestamp(stamp, sizeof stamp);
    va_list args;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    /* One call per line keeps lines whole if a GL thread logs later. */
    fprintf(stderr, "%s %-5s %s\n", stamp, fc_log_level_name(level), message);
}
