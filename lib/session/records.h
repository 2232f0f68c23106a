/*
 * records.h - the rig's records: a SQLite database (WAL mode) of the
 * sessions of a session directory (sessiondir.h), so that they are
 * listed and judged without reading their files. The files stay the
 * truth: a missing or damaged database is built again from them
 * (records_rebuild()), and records_check() says how the two differ.
 *
 * The schema (docs/SESSION_FORMAT.md, "The records"): trainees(id, name),
 * cases(id, name), sessions(id: the file's ID, trainee_id, case_id,
 * started, ended, path, bytes, checksum: FNV-1a of the whole file (its
 * frames' CRC-32s would cancel a whole-file CRC-32's change),
 * rig, judgement: "COURSE: passed|failed", NULL none, uuid: records_uuid(),
 * at_centre: 1 once a centre's database has it) and measures(session_id,
 * one column per metricstext_fields() key) for the sessions with an END
 * frame; centre_queue(seq, session_id): the sessions a centre's database
 * (centre.h) waits for, in the order they were written.
 * Its version is SQLite's user_version; the migrations are an ordered
 * list of SQL steps, each run once, in a transaction, from the database's
 * version up to RECORDS_SCHEMA_VERSION. A new measure is a new row of
 * metricstext_fields() and a migration adding its column.
 *
 * Each call opens the database, does its work and closes it again: a
 * database deleted or replaced meanwhile is noticed on the next call, and
 * readers (endoctl) may read beside the writer (WAL). Every statement that
 * carries a value binds it as a parameter.
 *
 * Reads the session files and writes the database, blocks on the disk,
 * allocates: the control thread or a tool, never the force loop. One
 * writer per database (endosimd, the directory's owner).
 */
#ifndef ENDOSIM_RECORDS_H
#define ENDOSIM_RECORDS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "session/metrics.h"
#include "session/sessiondir.h"

#define RECORDS_SCHEMA_VERSION 5
#define RECORDS_DEFAULT_NAME "records.sqlite"

struct records;

/* One session as the database (or its file) says. */
struct records_session {
	struct sessiondir_entry e;  /* id, bytes, ended, trainee, case,
				       started */
	uint64_t checksum;          /* FNV-1a (64 bits) of the whole file */
	char rig[64];               /* the rig that recorded it */
	char judgement[96];         /* "COURSE: passed" or "COURSE: failed"
				       by the course its case is in; "":
				       none (no course, not its case, no
				       END frame) */
	bool has_metrics;           /* m is its END frame's */
	struct metrics_result m;    /* the scalars; no episodes */
	char uuid[37];              /* records_uuid(): its key at a centre */
};

/* What records_check() or records_rebuild() found and did. */
struct records_report {
	bool missing;       /* no database at all */
	bool damaged;       /* SQLite could not read it, or its check failed */
	size_t files;       /* session files in the directory */
	size_t rows;        /* sessions in the database */
	size_t differ;      /* sessions whose row and file differ, or only
			       one of them is there */
	size_t written;     /* rows written (added, replaced, deleted) */
	char *text;         /* malloc'd: one line each thing found, "" */
};

/*
 * The records of the session directory DIR in the database DATABASE (a
 * relative path is taken under DIR), RIG the name written with each
 * session (NULL or "": the host's name), COURSE the course file
 * (coursefile.h) each session's judgement is written by (NULL or "":
 * none; read at each write: one that does not load judges nothing).
 * Touches nothing yet. NULL on ENOMEM.
 */
struct records *records_create(const char *database, const char *dir,
			       const char *rig, const char *course);
void records_destroy(struct records *r);

/* The database's path (DIR/records.sqlite by default). */
const char *records_path(const struct records *r);

/* This rig's name in the records (records_create()'s RIG, or the host's). */
const char *records_rig(const struct records *r);

/*
 * Why the last call failed, in words naming the database ("" when it did
 * not): a newer schema, SQLite's error.
 */
const char *records_error(const struct records *r);

/*
 * The session file DIR/ID.endoses read and written as its row (replacing
 * any), with its measures when it ends with an END frame: at a session's
 * end. A missing or damaged database is built again from every file
 * first. 0; -ENOENT (no such file: its row, if any, removed); -EPROTO (the
 * database's schema is newer than this program's); -EIO (SQLite's error);
 * -errno.
 */
int records_add(struct records *r, uint64_t id);

/*
 * As records_add(), the file's checksum *SUM known already (NULL: not):
 * its writer's, records_checksum() carried over every byte it wrote, so
 * that a long session's file is not read whole again at its end.
 */
int records_add_summed(struct records *r, uint64_t id, const uint64_t *sum);

/* The records' checksum of a file, FNV-1a (64 bits): SUM (the seed at the
 * file's start) carried over the N bytes at P. Any thread, no state. */
#define RECORDS_CHECKSUM_SEED 0xcbf29ce484222325ull
uint64_t records_checksum(uint64_t sum, const void *p, size_t n);

/* The checksum of the whole file PATH into *SUM. 0 or -errno (-EIO). */
int records_file_checksum(const char *path, uint64_t *sum);

/*
 * Every session of the database sorted by ID: a malloc'd array of *N in
 * *OUT (free() it). A missing or damaged database is built again from the
 * files first. 0 or as records_add().
 */
int records_list(struct records *r, struct records_session **out, size_t *n);

/*
 * Called with each session of records_each() in turn, S valid during the
 * call only: 0 to go on, else what records_each() returns. S NULL: forget
 * the sessions passed so far, they come again (the database was found
 * damaged midway, and is read again once built from the files).
 */
typedef int records_fn(void *arg, const struct records_session *s);

/* What records_each() reads of each session. */
enum {
	RECORDS_FACTS = 0,     /* its row alone: has_metrics false, m zero */
	RECORDS_MEASURES = 1,  /* its measures too, when it has them */
};

/*
 * The sessions of the database by ID, TRAINEE's alone (exactly; NULL:
 * everyone's), each read as WHAT says and passed to FN with ARG as it is
 * read: a listing holds no more than it keeps. With RECORDS_MEASURES and
 * KEYS, only the N_KEYS measures KEYS names (metricstext_fields()' keys;
 * the others left 0): what a course judges by. A missing or damaged
 * database is built again from the files first. 0, FN's nonzero return,
 * -EINVAL (a key names no measure), or as records_add().
 */
int records_each(struct records *r, const char *trainee, unsigned what,
		 const char *const *keys, size_t n_keys, records_fn *fn,
		 void *arg);

/* Flags of records_check(). */
enum {
	RECORDS_DEEP = 1,  /* read every file: its checksum and its measures,
			      not only that it is there and its size */
	RECORDS_FIX = 2,   /* write each row that differs from its file;
			      a damaged database: made again (as
			      records_rebuild()) */
};

/*
 * The database against the files of DIR (leaving out session SKIP, the
 * one recording; 0: none) into *REP (records_report_free() it). Without
 * RECORDS_FIX the database is only read (a missing one is not created).
 * 0 or as records_add(); *REP holds what was found even then.
 */
int records_check(struct records *r, unsigned flags, uint64_t skip,
		  struct records_report *rep);

/*
 * The database built again from the files (all but SKIP): a damaged one
 * moved aside to PATH.damaged, every row deleted and each file's written.
 * *REP as records_check()'s before the rebuild, and written. 0 or as
 * records_add().
 */
int records_rebuild(struct records *r, uint64_t skip,
		    struct records_report *rep);

void records_report_free(struct records_report *rep);

/*
 * An online copy of the database into the new file PATH (SQLite's backup
 * API; the copy in rollback-journal mode, one file), its sessions into
 * *ROWS. PATH must not exist, nor a link by that name: a backup replaces
 * nothing. 0; -EEXIST; -ENOENT (no database to copy); or as records_add()
 * (a failed copy's file removed).
 */
int records_backup(struct records *r, const char *path, size_t *rows);

/*
 * The database made again from the backup PATH, then brought up to date
 * with the files (all but SKIP, the session recording) as a check's fix
 * does: sessions recorded since the backup written, rows whose file is
 * gone removed, the files being the truth; what the backup alone holds of
 * the others (their centre's queue and marks) kept. PATH is checked whole
 * first: a file that is not a sound records database of this schema or
 * an older one is refused, the database left as it was. *REP as
 * records_check()'s (records_report_free() it). 0; -ENOENT; -EBADMSG (not
 * a sound records database); -EPROTO (a newer schema's); or as
 * records_add().
 */
int records_restore(struct records *r, const char *path, uint64_t skip,
		    struct records_report *rep);

/*
 * A centre's queue. With ON each session written (records_add(), a check's
 * fix, a rebuild) is queued for the centre too, in the same transaction
 * as its row; one queued already keeps its place. Off (the default): the
 * queue is left as it is.
 */
void records_set_centre(struct records *r, bool on);

/*
 * S's UUID into OUT ("xxxxxxxx-xxxx-8xxx-xxxx-xxxxxxxxxxxx", RFC 9562's
 * version 8): 128 bits of FNV-1a over its rig, ID, trainee, case and start,
 * so that a database built again from the files gives each session the
 * UUID it had, and the centre takes it once.
 */
void records_uuid(const struct records_session *s, char out[37]);

/*
 * Every session the centre is not known to have (at_centre 0: new, or
 * its database built again) queued, after those queued already: at
 * start-up. *WAITING: how many wait now. 0 or as records_add().
 */
int records_queue_unsent(struct records *r, size_t *waiting);

/*
 * The session that has waited longest for the centre into *S, and how
 * many wait (it among them) into *WAITING. 0; -ENOENT: none waits, or
 * the database is missing; or as records_add(). These two never build the
 * database again (its writer's calls do, queueing every session), so
 * that a second thread (the centre's) may call them beside the writer.
 */
int records_queue_head(struct records *r, struct records_session *s,
		       size_t *waiting);

/* Session ID arrived at the centre: out of the queue, marked at_centre
 * (nothing when the database is missing). 0 or as records_add(). */
int records_queue_arrived(struct records *r, uint64_t id);

/* The session file PATH as its row would be. 0; -errno; -EBADMSG. */
int records_read_file(const char *path, struct records_session *s);

#endif
