/*
 * json.h - a small streaming JSON writer for endoctl's --json output:
 * one object per call sequence, strings escaped, non-finite numbers written
 * as null. Nesting up to JSON_MAX_DEPTH.
 */
#ifndef ENDOSIM_JSON_H
#define ENDOSIM_JSON_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#define JSON_MAX_DEPTH 8

struct json {
	FILE *out;
	int depth;
	bool used[JSON_MAX_DEPTH]; /* a member already written at this level */
};

void json_init(struct json *j, FILE *out);

/* KEY is the member name inside an object, NULL inside an array or at the
 * top level. */
void json_object_begin(struct json *j, const char *key);
void json_object_end(struct json *j);
void json_array_begin(struct json *j, const char *key);
void json_array_end(struct json *j);
void json_string(struct json *j, const char *key, const char *value);
void json_double(struct json *j, const char *key, double value);
void json_uint(struct json *j, const char *key, uint64_t value);
void json_int(struct json *j, const char *key, int64_t value);
void json_bool(struct json *j, const char *key, bool value);

#endif
