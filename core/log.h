/* Logging to stderr, with a level threshold (--verbose / --quiet). */
#ifndef SL_LOG_H
#define SL_LOG_H
#include <shadelab/shadelab.h>
#include <stdarg.h>

extern sl_log_level sl_log_threshold;
void sl_log(sl_log_level level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void sl_logv(sl_log_level level, const char *prefix, const char *fmt, va_list ap);
/* Counts of warnings/errors printed so far (tests assert on them). */
int sl_log_count(sl_log_level level);
/* Captures everything logged into a buffer as well (tests); NULL stops. */
void sl_log_capture(char *buf, size_t size);
/* Every warning and error logged so far, one per line ("warning: …", "error: …"), bounded (the
 * oldest stay; a last line counts what did not fit). The window shows what loading left here. */
const char *sl_log_problems(void);

#define SL_DEBUG(...) sl_log(SL_LOG_DEBUG, __VA_ARGS__)
#define SL_INFO(...) sl_log(SL_LOG_INFO, __VA_ARGS__)
#define SL_WARN(...) sl_log(SL_LOG_WARN, __VA_ARGS__)
#define SL_ERROR(...) sl_log(SL_LOG_ERROR, __VA_ARGS__)
#endif
