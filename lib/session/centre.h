/*
 * centre.h - a training centre's records: one PostgreSQL database (libpq)
 * that every rig of the centre writes its sessions to, and that endoctl
 * reads a trainee's sessions from, whichever rig recorded them.
 *
 * The centre's URL is libpq's (postgresql://HOST[:PORT]/DBNAME?...,
 * or "host=... dbname=..."): its user, sslmode, service and the rest are
 * libpq's own; its password comes from libpq's password file (~/.pgpass,
 * PGPASSFILE) or service file, never from the URL (centre_check_url()
 * refuses one that holds a password). The connection waits at most
 * CENTRE_CONNECT_TIMEOUT_S to be made (libpq's connect_timeout, which the
 * URL may set otherwise).
 *
 * The schema (docs/SESSION_FORMAT.md, "A centre's records"): one table
 * sessions(uuid: records_uuid(), the key; arrival: the order the centre
 * took them in; rig; rig_session: the session's ID on its rig; trainee,
 * case_name, started, ended, bytes, judgement, has_measures; one column per
 * metricstext_fields() key; report: the instructor's page, report.h's
 * HTML; received). A writer (centre_connect(..., true)) makes the table,
 * and adds the columns of measures it has that the table lacks, under an
 * advisory lock, so that two rigs starting together do not race.
 *
 * The people (the rigs' accounts, accounts.h: docs/SESSION_FORMAT.md "A
 * centre's people"): endosim_people(name, role, pin: its Argon2id
 * string), endosim_groups(name, instructor), endosim_members(group_name,
 * trainee), endosim_courses(group_name, course), made by the rigs'
 * changes alone, each noted once in endosim_changes(id: the rig's random
 * ID of it, arrival: the order the centre took them in, rig, op, name,
 * group_name, course, applied, received); the last arrival is the
 * people's version. config/centre-roles.sql reads them for row-level
 * security.
 *
 * Every statement binds its values as parameters. Blocks on the network
 * (each call up to the connect timeout, or as long as the server takes to
 * answer), allocates: a worker thread or a tool, never the force loop, and
 * not the control thread. One struct centre per thread.
 */
#ifndef ENDOSIM_CENTRE_H
#define ENDOSIM_CENTRE_H

#include <stdbool.h>
#include <stddef.h>

#include "session/accounts.h"
#include "session/records.h"

#define CENTRE_CONNECT_TIMEOUT_S 5

struct centre;

/*
 * URL checked as libpq reads it: 0; -EINVAL with why in ERR (not a
 * connection string, or a password in it).
 */
int centre_check_url(const char *url, char *err, size_t size);

/*
 * The centre at URL, for the program APP (its application_name at the
 * server). Touches nothing yet. NULL on ENOMEM.
 */
struct centre *centre_create(const char *url, const char *app);
void centre_destroy(struct centre *c);

/* Why the last call failed, in words ("" when it did not). */
const char *centre_error(const struct centre *c);

/*
 * Connected (again, when the connection was lost); with WRITE the schema
 * made or completed. 0; -EINVAL (the URL); -ENOTCONN (the server cannot
 * be reached, or refused us: its words in centre_error()); -EIO (a
 * statement failed).
 */
int centre_connect(struct centre *c, bool write);

/* Whether a connection is held: one the server has closed since (a
 * restart) is known lost only when the next statement fails. */
bool centre_connected(const struct centre *c);

/* The connection closed (a later call connects again). */
void centre_disconnect(struct centre *c);

/*
 * Session S of the rig (its rig, uuid, header, measures) written with its
 * report page REPORT (NULL: none), unless the centre has its UUID
 * already: then nothing. 0 (written, or there already); -EBADMSG (the
 * centre refused the row's data: it will refuse it again); -ENOTCONN (the
 * connection was lost); -EIO.
 */
int centre_put(struct centre *c, const struct records_session *s,
	       const char *report);

/* Whether the centre has the session of UUID: 1, 0, or as centre_put(). */
int centre_has(struct centre *c, const char *uuid);

/*
 * TRAINEE's sessions (NULL: everyone's) from every rig, in the order
 * they started (then by rig and ID): a malloc'd array of *N in *OUT
 * (free() it), e.id the session's ID on its rig. 0 or as centre_put().
 */
int centre_list(struct centre *c, const char *trainee,
		struct records_session **out, size_t *n);

/* The report page of the session of UUID into *HTML (malloc'd; "" when it
 * has none). 0; -ENOENT; or as centre_put(). */
int centre_report(struct centre *c, const char *uuid, char **html);

/*
 * The instructor's report page (report.h) of the session file PATH into
 * *HTML (malloc'd), its metrics recomputed when the file was cut short.
 * 0 or -errno.
 */
int centre_report_page(const char *path, char **html);

/* What became of a change of a rig's accounts at the centre. */
enum centre_outcome {
	CENTRE_APPLIED,   /* it changed the centre's people */
	CENTRE_UNCHANGED, /* they were so already, or otherwise: a name the
			     centre has, added again, stays as it is */
	CENTRE_REFUSED,   /* the centre cannot apply it (a user or group it
			     lacks, an instructor who manages a group): its
			     people stand; why in centre_error() */
	CENTRE_TAKEN,     /* its ID was taken before: not applied again */
};

/*
 * The change Q of the accounts of the rig RIG applied to the centre's
 * people and noted in endosim_changes, in one transaction, unless its ID
 * is there already: its outcome into *OUT. Changes are taken one at a
 * time (a lock), so that their arrival is the order they commit in. 0;
 * -ENOTCONN; -EIO.
 */
int centre_change(struct centre *c, const char *rig,
		  const struct accounts_queued *q, enum centre_outcome *out);

/* The version of the centre's people (the last change's arrival, "0"
 * none) into OUT. 0; -ENOTCONN; -EIO. */
int centre_people_version(struct centre *c, char *out, size_t size);

struct pg_result;

/* The centre's people as accounts_replace() takes them. */
struct centre_people {
	char version[24];
	struct accounts_change *ch; /* its texts in res */
	size_t n;
	struct pg_result *res[5];
};

/*
 * The centre's people at one instant (one snapshot) into *P
 * (centre_people_free()): every person (USER_ADD, with their Argon2id
 * string), then every group, member and course. 0; -ENOTCONN; -EIO;
 * -ENOMEM.
 */
int centre_people(struct centre *c, struct centre_people *p);
void centre_people_free(struct centre_people *p);

#endif
