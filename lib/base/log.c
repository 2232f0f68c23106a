/* log.c - see log.h. */
#include "base/log.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mono.h"

_Atomic int log_max_level = LOG_INFO;
static const char *log_ident = "endosim";
static int log_journal;

static const char *const level_names[] = {
	[LOG_EMERG] = "emerg", [LOG_ALERT] = "alert", [LOG_CRIT] = "crit",
	[LOG_ERR] = "err",     [LOG_WARNING] = "warning",
	[LOG_NOTICE] = "notice", [LOG_INFO] = "info", [LOG_DEBUG] = "debug",
};

void log_init(const char *ident, int max_level)
{
	const char *js = getenv("JOURNAL_STREAM");

	log_ident = ident;
	log_max_level = max_level;
	log_journal = js && *js;
}

int log_level_parse(const char *name)
{
	for (int i = LOG_ERR; i <= LOG_DEBUG; i++) {
		if (!strcmp(name, level_names[i])) {
			return i;
		}
	}
	return -1;
}

const char *log_level_name(int level)
{
	return level >= LOG_EMERG && level <= LOG_DEBUG ? level_names[level]
							: "?";
}

void log_print(int level, const char *fmt, ...)
{
	char line[1024];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(line, sizeof(line), fmt, ap);
	va_end(ap);
	if (log_journal) {
		fprintf(stderr, "<%d>%s\n", level, line);
	} else if (level <= LOG_WARNING) {
		fprintf(stderr, "%s: %s: %s\n", log_ident,
			level == LOG_WARNING ? "warning" : "error", line);
	} else {
		fprintf(stderr, "%s: %s\n", log_ident, line);
	}
}

int log_ratelimit_pass(struct log_ratelimit *rl)
{
	int64_t now = (int64_t)mono_ns();

	if (now - rl->window_start_ns >= rl->interval_ns) {
		if (rl->suppressed) {
			log_print(LOG_NOTICE, "%u similar messages suppressed",
				  rl->suppressed);
		}
		rl->window_start_ns = now;
		rl->printed = 0;
		rl->suppressed = 0;
	}
	if (rl->printed < rl->burst) {
		rl->printed++;
		return 1;
	}
	rl->suppressed++;
	return 0;
}
