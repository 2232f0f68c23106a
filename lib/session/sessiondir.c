/* sessiondir.c - see sessiondir.h. */
#include "session/sessiondir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "proto/session_file.h"

#define TAIL_BYTES 65536 /* an END frame is a few hundred bytes */
#define HEADER_MAX 65536

int sessiondir_prepare(const char *dir)
{
	char path[4096];
	size_t n = strlen(dir);

	if (!n || n >= sizeof(path)) {
		return -ENAMETOOLONG;
	}
	memcpy(path, dir, n + 1);
	for (char *p = path + 1; *p; p++) {
		if (*p != '/') {
			continue;
		}
		*p = '\0';
		if (mkdir(path, 0750) < 0 && errno != EEXIST) {
			return -errno;
		}
		*p = '/';
	}
	if (mkdir(path, 0750) < 0 && errno != EEXIST) {
		return -errno;
	}
	return 0;
}

int sessiondir_path(const char *dir, uint64_t id, char *buf, size_t size)
{
	int n = snprintf(buf, size, "%s/%" PRIu64 SESSIONDIR_SUFFIX, dir, id);

	return n < 0 || (size_t)n >= size ? -ENAMETOOLONG : 0;
}

uint64_t sessiondir_file_id(const char *name)
{
	char *end;
	uint64_t id;

	if (name[0] < '1' || name[0] > '9') {
		return 0;
	}
	id = strtoull(name, &end, 10);
	return strcmp(end, SESSIONDIR_SUFFIX) ? 0 : id;
}

int sessiondir_next_id(const char *dir, uint64_t *id)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	uint64_t max = 0;

	if (!d) {
		return -errno;
	}
	while ((e = readdir(d))) {
		uint64_t k = sessiondir_file_id(e->d_name);

		max = k > max ? k : max;
	}
	closedir(d);
	*id = max + 1;
	return 0;
}

static uint32_t get_u32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

static int read_at(int fd, void *buf, size_t n, off_t off)
{
	ssize_t r = pread(fd, buf, n, off);

	return r < 0 ? -errno : (size_t)r == n ? 0 : -EBADMSG;
}

/* The header of the session file open as FD. */
static int read_header(int fd, char *buf, size_t size)
{
	unsigned char head[16];
	uint32_t len, crc, want;
	unsigned char *payload;
	int r = read_at(fd, head, sizeof(head), 0);

	if (r || memcmp(head, SESSION_FILE_MAGIC, 8) ||
	    get_u32(head + 8) != SESSION_FRAME_HEADER) {
		return r && r != -EBADMSG ? r : -EBADMSG;
	}
	len = get_u32(head + 12);
	payload = len <= HEADER_MAX ? malloc(len + 4u) : NULL;
	if (!payload) {
		return -EBADMSG;
	}
	r = read_at(fd, payload, len + 4u, 16);
	crc = session_crc32(session_crc32(0, head + 8, 8), payload, len);
	want = r ? 0 : get_u32(payload + len);
	if (!r && crc != want) {
		r = -EBADMSG;
	}
	if (!r) {
		snprintf(buf, size, "%.*s", (int)len, (const char *)payload);
	}
	free(payload);
	return r;
}

int sessiondir_header(const char *path, char *buf, size_t size)
{
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	int r;

	if (fd < 0) {
		return -errno;
	}
	r = read_header(fd, buf, size);
	close(fd);
	return r;
}

/* An intact END frame at OFF of TAIL, running exactly to its end? */
static bool end_frame_at(const unsigned char *tail, size_t n, size_t off)
{
	uint32_t len;

	if (get_u32(tail + off) != SESSION_FRAME_END) {
		return false;
	}
	len = get_u32(tail + off + 4);
	if (len > n || off + 12 + (size_t)len != n) {
		return false;
	}
	return session_crc32(0, tail + off, 8 + (size_t)len) ==
	       get_u32(tail + off + 8 + len);
}

/*
 * The intact END frame that ends the file open as FD of SIZE bytes: its
 * payload (malloc'd, NUL-terminated) in *TEXT when TEXT is not NULL.
 * True when there is one.
 */
static bool find_end(int fd, uint64_t size, char **text)
{
	size_t n = size < TAIL_BYTES ? (size_t)size : TAIL_BYTES;
	unsigned char *tail = malloc(n ? n : 1);
	bool ended = false;
	size_t off;

	if (!tail || n < 12 || read_at(fd, tail, n, (off_t)(size - n))) {
		free(tail);
		return false;
	}
	for (off = n - 12; !ended; off--) {
		ended = end_frame_at(tail, n, off);
		if (ended || !off) {
			break;
		}
	}
	if (ended && text) {
		size_t len = n - off - 12;

		*text = malloc(len + 1);
		ended = *text != NULL;
		if (ended) {
			memcpy(*text, tail + off + 8, len);
			(*text)[len] = '\0';
		}
	}
	free(tail);
	return ended;
}

bool sessiondir_ended(int fd, uint64_t size)
{
	return find_end(fd, size, NULL);
}

int sessiondir_end_text(const char *path, char **text)
{
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	struct stat st;
	int r = 0;

	*text = NULL;
	if (fd < 0 || fstat(fd, &st) < 0) {
		r = -errno;
	} else if (!find_end(fd, (uint64_t)st.st_size, text)) {
		r = -ENOENT;
	}
	if (fd >= 0) {
		close(fd);
	}
	return r;
}

static void header_value(const char *text, const char *key, char *out,
			 size_t size)
{
	if (session_text_get(text, key, out, size)) {
		out[0] = '\0';
	}
}

int sessiondir_stat_file(const char *path, struct sessiondir_entry *e)
{
	char *header = malloc(HEADER_MAX), id[32];
	struct stat st;
	int fd, r;

	if (!header) {
		return -ENOMEM;
	}
	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0 || fstat(fd, &st) < 0) {
		r = -errno;
		goto out;
	}
	r = read_header(fd, header, HEADER_MAX);
	if (!r) {
		*e = (struct sessiondir_entry){ .bytes = (uint64_t)st.st_size };
		if (!session_text_get(header, "id", id, sizeof(id))) {
			e->id = strtoull(id, NULL, 10);
		}
		e->ended = sessiondir_ended(fd, (uint64_t)st.st_size);
		header_value(header, "trainee", e->trainee, sizeof(e->trainee));
		header_value(header, "case", e->case_name, sizeof(e->case_name));
		header_value(header, "started", e->started, sizeof(e->started));
	}
out:
	if (fd >= 0) {
		close(fd);
	}
	free(header);
	return r;
}

int sessiondir_stat(const char *dir, uint64_t id, struct sessiondir_entry *e)
{
	char path[4096];
	int r = sessiondir_path(dir, id, path, sizeof(path));

	if (!r) {
		r = sessiondir_stat_file(path, e);
	}
	if (!r) {
		e->id = id; /* its file's name */
	}
	return r;
}

static int by_id(const void *a, const void *b)
{
	uint64_t x = ((const struct sessiondir_entry *)a)->id;
	uint64_t y = ((const struct sessiondir_entry *)b)->id;

	return x < y ? -1 : x > y;
}

/* Appends the entry of ID to *OUT if it is a session file. */
static int add_entry(const char *dir, uint64_t id,
		     struct sessiondir_entry **out, size_t *n, size_t *cap)
{
	struct sessiondir_entry e;

	if (sessiondir_stat(dir, id, &e)) {
		return 0;
	}
	if (*n == *cap) {
		size_t c = *cap ? 2 * *cap : 16;
		struct sessiondir_entry *bigger = realloc(*out, c * sizeof(e));

		if (!bigger) {
			return -ENOMEM;
		}
		*out = bigger;
		*cap = c;
	}
	(*out)[(*n)++] = e;
	return 0;
}

int sessiondir_list(const char *dir, struct sessiondir_entry **out,
		    size_t *n)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	size_t cap = 0;
	int r = 0;

	*out = NULL;
	*n = 0;
	if (!d) {
		return -errno;
	}
	while (!r && (e = readdir(d))) {
		uint64_t id = sessiondir_file_id(e->d_name);

		r = id ? add_entry(dir, id, out, n, &cap) : 0;
	}
	closedir(d);
	if (r) {
		free(*out);
		*out = NULL;
		*n = 0;
		return r;
	}
	if (*n) { /* an empty directory: no array to sort */
		qsort(*out, *n, sizeof(**out), by_id);
	}
	return 0;
}
