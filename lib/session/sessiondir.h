/*
 * sessiondir.h - the directory of recorded sessions ([session] directory):
 * files ID.endoses, ID a decimal number counting up from 1, and what a
 * listing shows of each without reading its records (the HEADER frame,
 * whether it ends with an END frame, its size).
 *
 * Reads and creates files: never the force loop. No shared state.
 */
#ifndef ENDOSIM_SESSIONDIR_H
#define ENDOSIM_SESSIONDIR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define SESSIONDIR_SUFFIX ".endoses"

struct sessiondir_entry {
	uint64_t id;
	uint64_t bytes;       /* file size */
	bool ended;           /* the last frame is an intact END */
	char trainee[64];
	char case_name[64];
	char started[32];     /* the header's, UTC */
};

/* Creates DIR and its missing parents (mode 0750). 0 or -errno. */
int sessiondir_prepare(const char *dir);

/* DIR/ID.endoses into BUF. 0 or -ENAMETOOLONG. */
int sessiondir_path(const char *dir, uint64_t id, char *buf, size_t size);

/* The largest ID in DIR plus one (1 in an empty one). 0 or -errno. */
int sessiondir_next_id(const char *dir, uint64_t *id);

/*
 * The HEADER frame's text of the session file PATH, NUL-terminated, into
 * BUF (cut to SIZE). 0; -errno; -EBADMSG when PATH is not a session file.
 */
int sessiondir_header(const char *path, char *buf, size_t size);

/* True when the file open as FD of SIZE bytes ends with an intact END. */
bool sessiondir_ended(int fd, uint64_t size);

/*
 * The END frame's text (metricstext_format()'s lines) of the session file
 * PATH, malloc'd and NUL-terminated, in *TEXT (free() it). 0; -ENOENT when
 * the file does not end with an intact END (cut short, still recording);
 * -errno.
 */
int sessiondir_end_text(const char *path, char **text);

/* The ID of a file named ID.endoses (ID decimal, from 1), else 0. */
uint64_t sessiondir_file_id(const char *name);

/*
 * The entry of the session file PATH, its id from its header (0 when the
 * header has none). 0; -errno (-ENOENT: no such file); -EBADMSG (not a
 * session file).
 */
int sessiondir_stat_file(const char *path, struct sessiondir_entry *e);

/*
 * The entry of session ID in DIR. 0; -ENOENT (no such session); -EBADMSG
 * (not a session file).
 */
int sessiondir_stat(const char *dir, uint64_t id, struct sessiondir_entry *e);

/*
 * Every session in DIR sorted by ID: a malloc'd array of *N entries in
 * *OUT (free() it); files that are not session files are left out. 0 or
 * -errno.
 */
int sessiondir_list(const char *dir, struct sessiondir_entry **out,
		    size_t *n);

#endif
