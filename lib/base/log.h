/*
 * log.h - leveled logging to stderr (the journal under systemd).
 *
 * The macros test the level before formatting anything. Under systemd
 * (JOURNAL_STREAM set) each line carries its syslog priority as a "<N>"
 * prefix, which journald turns into the entry's priority; on a terminal
 * lines read "endosimd: warning: ...".
 *
 * Thread-safe. Never call from the force loop: it posts event codes to a
 * ring instead (loop.h) and another thread logs them.
 */
#ifndef ENDOSIM_LOG_H
#define ENDOSIM_LOG_H

#include <stdatomic.h>
#include <stdint.h>
#include <syslog.h>

/* The most verbose level printed; any thread may change it. */
extern _Atomic int log_max_level;

/* Program name for the prefix, and the most verbose level printed. */
void log_init(const char *ident, int max_level);

/* Parses "err", "warning", "notice", "info", "debug". Returns -1 if unknown. */
int log_level_parse(const char *name);

/* The name of a syslog level, as log_level_parse() takes it. */
const char *log_level_name(int level);

void log_print(int level, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

#define log_at(level, ...)                        \
	do {                                      \
		if (atomic_load_explicit(&log_max_level,       \
					 memory_order_relaxed) >= (level)) { \
			log_print((level), __VA_ARGS__); \
		}                                 \
	} while (0)

#define log_err(...) log_at(LOG_ERR, __VA_ARGS__)
#define log_warn(...) log_at(LOG_WARNING, __VA_ARGS__)
#define log_notice(...) log_at(LOG_NOTICE, __VA_ARGS__)
#define log_info(...) log_at(LOG_INFO, __VA_ARGS__)
#define log_debug(...) log_at(LOG_DEBUG, __VA_ARGS__)

/*
 * Rate limiting for messages that can repeat: at most log_ratelimit.burst
 * lines per interval; the number suppressed is reported with the next line
 * that passes. One struct per message site, used by one thread.
 */
struct log_ratelimit {
	int64_t interval_ns;
	unsigned int burst;
	int64_t window_start_ns;
	unsigned int printed;
	unsigned int suppressed;
};

#define LOG_RATELIMIT_INIT(interval_s, burst_lines) \
	{ .interval_ns = (int64_t)(interval_s) * 1000000000LL, .burst = (burst_lines) }

/* True if a line may be printed now; counts it either way. */
int log_ratelimit_pass(struct log_ratelimit *rl);

#define log_ratelimited(rl, level, ...)                                    \
	do {                                                               \
		if (atomic_load_explicit(&log_max_level,                   \
					 memory_order_relaxed) >= (level) && \
		    log_ratelimit_pass(rl)) {                              \
			log_print((level), __VA_ARGS__);                   \
		}                                                          \
	} while (0)

#endif
