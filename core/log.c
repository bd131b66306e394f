#include "log.h"
#include <pthread.h>
#include <stdio.h>
#include <string.h>

sl_log_level sl_log_threshold = SL_LOG_INFO;
static int counts[4];
static char *capture_buf;
static size_t capture_size;
static char problems[6144];
static int problems_dropped;

const char *sl_log_problems(void) {
    static char out[sizeof problems + 64];
    snprintf(out, sizeof out, "%s", problems);
    if (problems_dropped) {
        size_t l = strlen(out);
        snprintf(out + l, sizeof out - l, "… and %d more (stderr has them all)\n", problems_dropped);
    }
    return out;
}

void sl_log_capture(char *buf, size_t size) {
    capture_buf = buf;
    capture_size = size;
    if (buf && size) buf[0] = 0;
}

int sl_log_count(sl_log_level level) { return counts[level]; }

/* one message at a time: textures are decoded on a worker thread (render/texture_prefetch.c) */
static pthread_mutex_t log_lock = PTHREAD_MUTEX_INITIALIZER;

void sl_logv(sl_log_level level, const char *prefix, const char *fmt, va_list ap) {
    pthread_mutex_lock(&log_lock);
    counts[level]++;
    static const char *names[] = {"debug", "info", "warning", "error"};
    char msg[4096];
    vsnprintf(msg, sizeof msg, fmt, ap);
    char line[4300];
    if (level == SL_LOG_INFO)
        snprintf(line, sizeof line, "%s%s%s\n", prefix ? prefix : "", prefix ? ": " : "", msg);
    else
        snprintf(line, sizeof line, "%s: %s%s%s\n", names[level], prefix ? prefix : "",
                 prefix ? ": " : "", msg);
    if (capture_buf) {
        size_t used = strlen(capture_buf);
        if (used + 1 < capture_size) snprintf(capture_buf + used, capture_size - used, "%s", line);
    }
    if (level >= SL_LOG_WARN) {
        size_t used = strlen(problems), len = strlen(line);
        if (used + len < sizeof problems) memcpy(problems + used, line, len + 1);
        else problems_dropped++;
    }
    if (level >= sl_log_threshold) fputs(line, stderr);
    pthread_mutex_unlock(&log_lock);
}

void sl_log(sl_log_level level, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sl_logv(level, NULL, fmt, ap);
    va_end(ap);
}
