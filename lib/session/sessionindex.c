/* sessionindex.c - see sessionindex.h. */
#include "session/sessionindex.h"
#include "session/metricstext.h"

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

#define MAGIC "endosim-session-index 1"
#define LINE_MAX_BYTES 8192
#define NFIELDS 9

/* One line of the index, or one file of the directory. */
struct item {
	struct sessionindex_entry x;
	bool bad;     /* not a session file */
	bool seen;    /* an index line: its file is there */
};

struct list {
	struct item *v;
	size_t n, cap;
};

static int list_add(struct list *l, const struct item *it)
{
	if (l->n == l->cap) {
		size_t c = l->cap ? 2 * l->cap : 16;
		struct item *bigger = realloc(l->v, c * sizeof(*bigger));

		if (!bigger) {
			return -ENOMEM;
		}
		l->v = bigger;
		l->cap = c;
	}
	l->v[l->n++] = *it;
	return 0;
}

static int by_id(const void *a, const void *b)
{
	uint64_t x = ((const struct item *)a)->x.e.id;
	uint64_t y = ((const struct item *)b)->x.e.id;

	return x < y ? -1 : x > y;
}

const char *sessionindex_state_name(enum sessionindex_state s)
{
	static const char *const names[] = { "fresh", "missing", "stale",
					     "damaged" };

	return (unsigned)s < 4 ? names[s] : "?";
}

/* ------------------------------------------------------------ a line */

/* "k=v k=v" (or "-") into M; 0 or -EINVAL. */
static int parse_metrics(char *text, struct metrics_result *m)
{
	for (char *c = text; *c; c++) {
		*c = *c == ' ' ? '\n' : *c;
	}
	return metricstext_parse(text, m);
}

static int parse_u64(const char *s, uint64_t *out)
{
	char *end;

	errno = 0;
	*out = strtoull(s, &end, 10);
	return errno || end == s || *end || *s == '-' ? -EINVAL : 0;
}

/* Copies S into OUT (SIZE) unless it is too long. */
static int copy_text(char *out, size_t size, const char *s)
{
	size_t n = strlen(s);

	if (n >= size) {
		return -EINVAL;
	}
	memcpy(out, s, n + 1);
	return 0;
}

/* Checks LINE's CRC and splits it at its tabs into F. */
static int split_line(char *line, char *f[NFIELDS])
{
	char *crc = strrchr(line, '\t'), *end;
	unsigned long want;

	if (!crc) {
		return -EINVAL;
	}
	*crc++ = '\0';
	want = strtoul(crc, &end, 16);
	if (strlen(crc) != 8 || *end ||
	    session_crc32(0, line, strlen(line)) != want) {
		return -EINVAL;
	}
	f[0] = line;
	for (int i = 1; i < NFIELDS - 1; i++) {
		if (!(f[i] = strchr(f[i - 1], '\t'))) {
			return -EINVAL;
		}
		*f[i]++ = '\0';
	}
	f[NFIELDS - 1] = crc;
	return strchr(f[NFIELDS - 2], '\t') ? -EINVAL : 0;
}

static int parse_line(char *line, struct item *it)
{
	struct sessiondir_entry *e = &it->x.e;
	char *f[NFIELDS];
	uint64_t mtime;

	memset(it, 0, sizeof(*it));
	if (split_line(line, f) || parse_u64(f[0], &e->id) || !e->id ||
	    parse_u64(f[1], &e->bytes) || parse_u64(f[2], &mtime) ||
	    copy_text(e->trainee, sizeof(e->trainee), f[4]) ||
	    copy_text(e->case_name, sizeof(e->case_name), f[5]) ||
	    copy_text(e->started, sizeof(e->started), f[6])) {
		return -EINVAL;
	}
	it->x.mtime_ns = (int64_t)mtime;
	it->bad = !strcmp(f[3], "bad");
	e->ended = !strcmp(f[3], "ended");
	if (!e->ended && !it->bad && strcmp(f[3], "cut")) {
		return -EINVAL;
	}
	it->x.has_metrics = e->ended;
	return e->ended ? parse_metrics(f[7], &it->x.m)
			: strcmp(f[7], "-") ? -EINVAL : 0;
}

/* The lines of the index file PATH into L (sorted by id); its state. */
static int read_index(const char *path, struct list *l,
		      struct sessionindex_info *info)
{
	FILE *f = fopen(path, "re");
	char *line;
	struct item it;
	int r = 0;

	if (!f) {
		info->state = SESSIONINDEX_MISSING; /* unreadable: as good as */
		return 0;
	}
	line = malloc(LINE_MAX_BYTES);
	if (!line) {
		r = -ENOMEM;
		goto out;
	}
	if (!fgets(line, LINE_MAX_BYTES, f) || strcmp(line, MAGIC "\n")) {
		info->bad_lines++; /* none of it can be trusted */
		goto out;
	}
	while (!r && fgets(line, LINE_MAX_BYTES, f)) {
		size_t n = strlen(line);

		if (!n || line[n - 1] != '\n' || (line[n - 1] = '\0',
		    parse_line(line, &it))) {
			info->bad_lines++;
			continue;
		}
		r = list_add(l, &it);
	}
	if (l->n) {
		qsort(l->v, l->n, sizeof(*l->v), by_id);
	}
out:
	fclose(f);
	free(line);
	return r;
}

/* ------------------------------------------------------ the directory */

/* What the file PATH says: its header and its END frame's metrics. */
static void read_file(const char *path, struct item *it)
{
	struct sessiondir_entry *e = &it->x.e;
	uint64_t id = e->id, bytes = e->bytes;
	char *end = NULL;
	int r = sessiondir_stat_file(path, e);

	e->id = id;
	e->bytes = bytes; /* the size the index is checked against */
	it->bad = r != 0;
	it->x.has_metrics = !r && e->ended && !sessiondir_end_text(path, &end) &&
			    !metricstext_parse(end, &it->x.m);
	it->x.m.n_force = it->x.m.n_loop = it->x.m.n_pain = 0;
	free(end);
}

/* The index's line for the file of IT if it still matches, else NULL. */
static struct item *match(struct list *index, const struct item *it)
{
	struct item *hit = index->n ? bsearch(it, index->v, index->n,
					      sizeof(*it), by_id) : NULL;

	if (!hit || hit->x.e.bytes != it->x.e.bytes ||
	    hit->x.mtime_ns != it->x.mtime_ns) {
		return NULL;
	}
	hit->seen = true;
	return hit;
}

/* One file of DIR named NAME into FILES, from INDEX or read. */
static int add_file(const char *dir, const char *name, struct list *index,
		    struct list *files, struct sessionindex_info *info)
{
	char path[4096];
	struct item it = { 0 }, *hit;
	struct stat st;

	it.x.e.id = sessiondir_file_id(name);
	if (!it.x.e.id ||
	    sessiondir_path(dir, it.x.e.id, path, sizeof(path)) ||
	    stat(path, &st) || !S_ISREG(st.st_mode)) {
		return 0; /* not a session's name, or gone meanwhile */
	}
	it.x.e.bytes = (uint64_t)st.st_size;
	it.x.mtime_ns = (int64_t)st.st_mtim.tv_sec * (int64_t)ENDOSIM_NS_PER_S +
			st.st_mtim.tv_nsec;
	if ((hit = match(index, &it))) {
		return list_add(files, hit);
	}
	read_file(path, &it);
	info->reread++;
	return list_add(files, &it);
}

static int scan(const char *dir, struct list *index, struct list *files,
		struct sessionindex_info *info)
{
	DIR *d = opendir(dir);
	struct dirent *de;
	int r = 0;

	if (!d) {
		return -errno;
	}
	while (!r && (de = readdir(d))) {
		r = add_file(dir, de->d_name, index, files, info);
	}
	closedir(d);
	if (files->n) {
		qsort(files->v, files->n, sizeof(*files->v), by_id);
	}
	return r;
}

/* -------------------------------------------------------------- write */

/* S with control characters (a tab, a newline) as '?'. */
static void put_text(FILE *f, const char *s)
{
	for (; *s; s++) {
		fputc((unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s, f);
	}
}

static int write_line(FILE *f, const struct item *it)
{
	const struct sessiondir_entry *e = &it->x.e;
	char *line = NULL, metrics[4096] = "-";
	size_t len = 0;
	FILE *m = open_memstream(&line, &len);
	int r = 0;

	if (!m) {
		return -ENOMEM;
	}
	if (it->x.has_metrics &&
	    metricstext_format(&it->x.m, metrics, sizeof(metrics)) > 0) {
		for (char *c = metrics; *c; c++) {
			*c = *c == '\n' ? ' ' : *c;
		}
		metrics[strlen(metrics) - 1] = '\0'; /* the last separator */
	}
	fprintf(m, "%" PRIu64 "\t%" PRIu64 "\t%" PRId64 "\t%s\t", e->id,
		e->bytes, it->x.mtime_ns, it->bad ? "bad" : it->x.has_metrics
		? "ended" : "cut");
	put_text(m, e->trainee);
	fputc('\t', m);
	put_text(m, e->case_name);
	fputc('\t', m);
	put_text(m, e->started);
	fprintf(m, "\t%s", it->x.has_metrics ? metrics : "-");
	if (fclose(m)) {
		r = -ENOMEM;
	} else if (fprintf(f, "%s\t%08" PRIx32 "\n", line,
			   session_crc32(0, line, len)) < 0) {
		r = -EIO;
	}
	free(line);
	return r;
}

/* FILES as DIR/index: a temporary file renamed over it. */
static int write_index(const char *dir, const struct list *files)
{
	char path[4096], tmp[4200];
	FILE *f;
	int fd, r = 0;

	snprintf(path, sizeof(path), "%s/" SESSIONINDEX_NAME, dir);
	snprintf(tmp, sizeof(tmp), "%s.XXXXXX", path);
	fd = mkstemp(tmp);
	if (fd < 0) {
		return -errno;
	}
	f = fdopen(fd, "w");
	if (!f) {
		r = -errno;
		close(fd);
		unlink(tmp);
		return r;
	}
	fchmod(fd, 0640);
	fputs(MAGIC "\n", f);
	for (size_t i = 0; i < files->n && !r; i++) {
		r = write_line(f, &files->v[i]);
	}
	/* not fsynced: a cache, rewritten while a session records; one torn
	 * by a crash is damaged, and built again */
	if (fflush(f)) {
		r = r ? r : -errno;
	}
	if (fclose(f) && !r) {
		r = -errno;
	}
	if (!r && rename(tmp, path)) {
		r = -errno;
	}
	if (r) {
		unlink(tmp);
	}
	return r;
}

/* ----------------------------------------------------------- the load */

/* The state the index was in, from what the load found. */
static enum sessionindex_state judge(const struct list *index,
				     const struct sessionindex_info *info)
{
	if (info->state == SESSIONINDEX_MISSING) {
		return SESSIONINDEX_MISSING;
	}
	if (info->bad_lines) {
		return SESSIONINDEX_DAMAGED;
	}
	for (size_t i = 0; i < index->n; i++) {
		if (!index->v[i].seen) {
			return SESSIONINDEX_STALE; /* its file is gone */
		}
	}
	return info->reread ? SESSIONINDEX_STALE : SESSIONINDEX_FRESH;
}

/* The session files of FILES into *OUT. */
static int keep_sessions(const struct list *files,
			 struct sessionindex_entry **out, size_t *n)
{
	*out = malloc((files->n ? files->n : 1) * sizeof(**out));
	if (!*out) {
		return -ENOMEM;
	}
	for (size_t i = 0; i < files->n; i++) {
		if (!files->v[i].bad) {
			(*out)[(*n)++] = files->v[i].x;
		}
	}
	return 0;
}

int sessionindex_load(const char *dir, bool write,
		      struct sessionindex_entry **out, size_t *n,
		      struct sessionindex_info *info)
{
	struct list index = { 0 }, files = { 0 };
	char path[4096];
	int r;

	*out = NULL;
	*n = 0;
	memset(info, 0, sizeof(*info));
	snprintf(path, sizeof(path), "%s/" SESSIONINDEX_NAME, dir);
	r = read_index(path, &index, info);
	if (!r) {
		r = scan(dir, &index, &files, info);
	}
	if (!r) {
		info->state = judge(&index, info);
		if (write && info->state != SESSIONINDEX_FRESH) {
			info->write_error = write_index(dir, &files);
		}
		r = keep_sessions(&files, out, n);
	}
	free(index.v);
	free(files.v);
	return r;
}
