/* log.h — timestamped, leveled log lines on stderr. The logger is a value
 * passed to whoever logs, so there is no global logging state. */
#ifndef FC_DAEMON_LOG_H
#define FC_DAEMON_LOG_H

#include "fluidcast_types.h"

typedef enum fc_log_level {
    FC_LOG_ERROR = 0,
    FC_LOG_WARN,
    FC_LOG_INFO,
    FC_LOG_DEBUG
} fc_log_level;

typedef struct fc_log {
    fc_log_level level;   /* lines above this level are dropped */
} fc_log;

/* Parses "error", "warn", "info" or "debug". */
fc_code fc_log_level_parse(const char *text, fc_log_level *out, fc_error *err);
const char *fc_log_level_name(fc_log_level level);

/* Writes "2024-05-01T12:00:00.123Z info  <message>" when level is enabled. */
void fc_log_write(const fc_log *log, fc_log_level level, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
