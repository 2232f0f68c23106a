/* json.c - see json.h. */
#include "base/json.h"

#include <inttypes.h>
#include <math.h>

void json_init(struct json *j, FILE *out)
{
	j->out = out;
	j->depth = 0;
	j->used[0] = false;
}

static void put_string(FILE *out, const char *s)
{
	fputc('"', out);
	for (; s && *s; s++) {
		unsigned char ch = (unsigned char)*s;

		if (ch == '"' || ch == '\\') {
			fprintf(out, "\\%c", ch);
		} else if (ch < 0x20) {
			fprintf(out, "\\u%04x", ch);
		} else {
			fputc(ch, out);
		}
	}
	fputc('"', out);
}

static void member(struct json *j, const char *key)
{
	if (j->used[j->depth]) {
		fputc(',', j->out);
	}
	j->used[j->depth] = true;
	if (key) {
		put_string(j->out, key);
		fputc(':', j->out);
	}
}

static void open_level(struct json *j, const char *key, char ch)
{
	member(j, key);
	fputc(ch, j->out);
	if (j->depth + 1 < JSON_MAX_DEPTH) {
		j->depth++;
	}
	j->used[j->depth] = false;
}

static void close_level(struct json *j, char ch)
{
	fputc(ch, j->out);
	if (j->depth > 0) {
		j->depth--;
	}
	if (j->depth == 0) {
		fputc('\n', j->out);
	}
}

void json_object_begin(struct json *j, const char *key)
{
	open_level(j, key, '{');
}

void json_object_end(struct json *j)
{
	close_level(j, '}');
}

void json_array_begin(struct json *j, const char *key)
{
	open_level(j, key, '[');
}

void json_array_end(struct json *j)
{
	close_level(j, ']');
}

void json_string(struct json *j, const char *key, const char *value)
{
	member(j, key);
	put_string(j->out, value);
}

void json_double(struct json *j, const char *key, double value)
{
	member(j, key);
	if (isfinite(value)) {
		fprintf(j->out, "%.9g", value);
	} else {
		fputs("null", j->out);
	}
}

void json_uint(struct json *j, const char *key, uint64_t value)
{
	member(j, key);
	fprintf(j->out, "%" PRIu64, value);
}

void json_int(struct json *j, const char *key, int64_t value)
{
	member(j, key);
	fprintf(j->out, "%" PRId64, value);
}

void json_bool(struct json *j, const char *key, bool value)
{
	member(j, key);
	fputs(value ? "true" : "false", j->out);
}
