/*
 * accounts.h - who may see what of the rig's records (docs/INSTRUCTOR.md,
 * "Who sees what"): users with a name, a role and a PIN; groups of
 * trainees (a year's intake), each managed by one instructor, with the
 * courses assigned to it. A SQLite database of its own, beside the
 * records (ACCOUNTS_DEFAULT_NAME in the records' directory): the records
 * are made again from the session files whenever they are missing or
 * damaged, the accounts are nobody's copy and must outlive that.
 *
 * The schema (user_version ACCOUNTS_SCHEMA_VERSION): users(name, role:
 * "trainee" | "instructor" | "administrator", pin: crypto_pwhash_str()'s
 * string (Argon2id, its salt and cost in it; never the PIN), failures,
 * wait_until: seconds since the epoch before which a login is refused);
 * groups(name, instructor: a user of role instructor); members(group,
 * trainee: a user of role trainee); courses(group, course: a course file's
 * name or path). A user is removed with their memberships; an instructor
 * who manages a group is not (-EBUSY), nor a group's last word about
 * anyone: removing a group removes its memberships and courses only.
 *
 * A trainee sees only the sessions whose trainee is their name; an
 * instructor those of the trainees of the groups they manage; an
 * administrator every session, and only an administrator deletes
 * records. Who changes the accounts is accounts_may()'s rule
 * (control_accounts.c applies both).
 *
 * PINs: 4 to ACCOUNTS_PIN_MAX characters, no control characters; hashed
 * with Argon2id at ACCOUNTS_PIN_OPS passes over ACCOUNTS_PIN_MEM bytes
 * (OWASP's floor for Argon2id: about 40 ms a hash on a 2020 laptop core).
 * A wrong PIN counts against its user: after ACCOUNTS_FREE_TRIES wrong
 * PINs in a row each further one makes the next try wait, 1 s, then
 * twice as long each time up to ACCOUNTS_WAIT_MAX_S; a try while it waits
 * is refused without looking at the PIN. A right PIN clears the count.
 * An unknown name costs the same hash as a known one and is refused in
 * the same words.
 *
 * Each call opens the database, does its work and closes it. Blocks on
 * the disk and, for a PIN, on the hash (tens of ms); allocates: the
 * control thread, the centre's worker or a tool, never the force loop.
 * Writers: endosimd's control thread and its centre's worker, each with a
 * struct accounts of its own (SQLite's locks between them).
 */
#ifndef ENDOSIM_ACCOUNTS_H
#define ENDOSIM_ACCOUNTS_H

#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#define ACCOUNTS_SCHEMA_VERSION 2
#define ACCOUNTS_DEFAULT_NAME "accounts.sqlite"
#define ACCOUNTS_NAME_MAX 63        /* bytes of a user's or group's name */
#define ACCOUNTS_COURSE_MAX 4095    /* bytes of a course's name or path */
#define ACCOUNTS_HASH_MAX 127       /* bytes of a PIN's Argon2id string */
#define ACCOUNTS_PIN_MIN 4
#define ACCOUNTS_PIN_MAX 64
#define ACCOUNTS_PIN_OPS 2          /* Argon2id passes */
#define ACCOUNTS_PIN_MEM (19u << 20) /* Argon2id memory, bytes */
#define ACCOUNTS_FREE_TRIES 3
#define ACCOUNTS_WAIT_MAX_S 300.0

enum accounts_role {
	ACCOUNTS_TRAINEE,
	ACCOUNTS_INSTRUCTOR,
	ACCOUNTS_ADMINISTRATOR,
};

struct accounts;

/* One user as the database says (never their PIN). */
struct accounts_user {
	char name[ACCOUNTS_NAME_MAX + 1];
	enum accounts_role role;
};

/* One group: its members and courses, each on a line of its own
 * (malloc'd, "" none; accounts_groups_free()). */
struct accounts_group {
	char name[ACCOUNTS_NAME_MAX + 1];
	char instructor[ACCOUNTS_NAME_MAX + 1];
	char *trainees;
	char *courses;
};

/* "trainee", "instructor", "administrator" (inline, as the ops' names
 * below: centre.c has them without linking SQLite or libsodium). */
static inline const char *accounts_role_name(enum accounts_role role)
{
	static const char *const names[] = {
		[ACCOUNTS_TRAINEE] = "trainee",
		[ACCOUNTS_INSTRUCTOR] = "instructor",
		[ACCOUNTS_ADMINISTRATOR] = "administrator",
	};

	return role <= ACCOUNTS_ADMINISTRATOR ? names[role] : "?";
}

/* NAME as a role into *ROLE: 0 or -EINVAL. */
static inline int accounts_role_parse(const char *name,
				      enum accounts_role *role)
{
	for (int i = 0; i <= ACCOUNTS_ADMINISTRATOR; i++) {
		if (!strcmp(name, accounts_role_name((enum accounts_role)i))) {
			*role = (enum accounts_role)i;
			return 0;
		}
	}
	return -EINVAL;
}

/*
 * The accounts of the database PATH (made, mode 0600, on the first
 * change). Touches nothing yet. NULL on ENOMEM or when libsodium cannot
 * start.
 */
struct accounts *accounts_create(const char *path);
void accounts_destroy(struct accounts *a);

const char *accounts_path(const struct accounts *a);

/* Why the last call failed, in words fit for the one refused ("" when
 * it did not). */
const char *accounts_error(const struct accounts *a);

/*
 * A user NAME of ROLE with PIN added. 0; -EINVAL (a name or PIN out of
 * the rules above); -EEXIST; -EIO (SQLite's error).
 */
int accounts_user_add(struct accounts *a, const char *name,
		      enum accounts_role role, const char *pin);

/* User NAME's PIN replaced by PIN (its count of wrong ones cleared). 0;
 * -EINVAL; -ENOENT; -EIO. */
int accounts_user_pin(struct accounts *a, const char *name, const char *pin);

/* User NAME removed, with their memberships. 0; -ENOENT; -EBUSY (an
 * instructor who manages a group); -EIO. */
int accounts_user_remove(struct accounts *a, const char *name);

/*
 * NAME logged in with PIN at NOW_S (seconds since the epoch): their
 * account into *U. 0; -EACCES (no such user, or a wrong PIN: *WAIT_S the
 * wait this try has earned, 0 none); -EAGAIN (a try while they wait:
 * *WAIT_S how long still); -EIO.
 */
int accounts_login(struct accounts *a, const char *name, const char *pin,
		   double now_s, struct accounts_user *u, double *wait_s);

/* Every user, by name, into a malloc'd array of *N (free() it). 0; -EIO.
 * A database not made yet has none. */
int accounts_users(struct accounts *a, struct accounts_user **out,
		   size_t *n);

/* Group NAME managed by INSTRUCTOR (a user of that role) made. 0;
 * -EINVAL; -EEXIST; -ENOENT (no such instructor); -EIO. */
int accounts_group_add(struct accounts *a, const char *name,
		       const char *instructor);

/* Group NAME removed, with its memberships and courses. 0; -ENOENT;
 * -EIO. */
int accounts_group_remove(struct accounts *a, const char *name);

/* TRAINEE (a user of that role) into group NAME (JOIN), or out of it.
 * 0 (also when already so); -ENOENT (no such group or trainee); -EIO. */
int accounts_group_member(struct accounts *a, const char *name,
			  const char *trainee, bool join);

/* COURSE assigned to group NAME (ASSIGN), or no longer. 0; -EINVAL (an
 * empty course); -ENOENT; -EIO. */
int accounts_group_course(struct accounts *a, const char *name,
			  const char *course, bool assign);

/* Every group, by name (INSTRUCTOR non-NULL: only the groups they
 * manage), into a malloc'd array of *N (accounts_groups_free()). 0;
 * -EIO. */
int accounts_groups(struct accounts *a, const char *instructor,
		    struct accounts_group **out, size_t *n);
void accounts_groups_free(struct accounts_group *g, size_t n);

/*
 * The trainees that U sees, one a line, into *NAMES (malloc'd; free()
 * it): a trainee themself; an instructor their groups' trainees; an
 * administrator: *ALL set, *NAMES "". 0; -EIO.
 */
int accounts_seen(struct accounts *a, const struct accounts_user *u,
		  char **names, bool *all);

/* Whether TRAINEE is one of the lines of NAMES (accounts_seen()'s). */
bool accounts_among(const char *names, const char *trainee);

/* ------------------------------------------------- who changes what */

/* The changes of the accounts, each as the calls above make it. */
enum accounts_op {
	ACCOUNTS_USER_ADD,
	ACCOUNTS_USER_REMOVE,
	ACCOUNTS_USER_PIN,
	ACCOUNTS_GROUP_ADD,
	ACCOUNTS_GROUP_REMOVE,
	ACCOUNTS_GROUP_JOIN,
	ACCOUNTS_GROUP_LEAVE,
	ACCOUNTS_GROUP_ASSIGN,
	ACCOUNTS_GROUP_UNASSIGN,
};

/*
 * One change: its texts are not the struct's ("" where the change has
 * none). NAME: the user added, removed, whose PIN, who joins or leaves;
 * GROUP_ADD's instructor. ROLE: USER_ADD's. PIN: USER_ADD's and
 * USER_PIN's, the PIN itself where a user makes the change, its Argon2id
 * string on its way to or from a centre. GROUP, COURSE: the group's.
 */
struct accounts_change {
	enum accounts_op op;
	const char *name;
	enum accounts_role role;
	const char *pin;
	const char *group;
	const char *course;
};

/* "user_add", "user_remove", "user_pin", "group_add", ... "group_unassign":
 * the centre's words too. */
static inline const char *accounts_op_name(enum accounts_op op)
{
	static const char *const names[] = {
		[ACCOUNTS_USER_ADD] = "user_add",
		[ACCOUNTS_USER_REMOVE] = "user_remove",
		[ACCOUNTS_USER_PIN] = "user_pin",
		[ACCOUNTS_GROUP_ADD] = "group_add",
		[ACCOUNTS_GROUP_REMOVE] = "group_remove",
		[ACCOUNTS_GROUP_JOIN] = "group_join",
		[ACCOUNTS_GROUP_LEAVE] = "group_leave",
		[ACCOUNTS_GROUP_ASSIGN] = "group_assign",
		[ACCOUNTS_GROUP_UNASSIGN] = "group_unassign",
	};

	return op <= ACCOUNTS_GROUP_UNASSIGN ? names[op] : "?";
}

/* NAME as an op into *OP: 0 or -EINVAL. */
static inline int accounts_op_parse(const char *name, enum accounts_op *op)
{
	for (int i = 0; i <= ACCOUNTS_GROUP_UNASSIGN; i++) {
		if (!strcmp(name, accounts_op_name((enum accounts_op)i))) {
			*op = (enum accounts_op)i;
			return 0;
		}
	}
	return -EINVAL;
}

/*
 * Whether U may make the change CH:
 * - an administrator, any;
 * - an instructor: a trainee added (with a first PIN); the PIN of a
 *   trainee of the groups they manage; in the groups they manage, a
 *   trainee joined (one in no group, or in one of theirs already: a
 *   trainee of another instructor's group stays theirs) or left, a course
 *   assigned or unassigned. Never an instructor or administrator added,
 *   a user removed, a group made or removed, another's group touched;
 * - anyone: their own PIN.
 * 0; -EPERM (why, for the one refused, in accounts_error()); -EIO. A
 * change let through may still fail on its own terms (no such group, a
 * name taken): the call that makes it says so.
 */
int accounts_may(struct accounts *a, const struct accounts_user *u,
		 const struct accounts_change *ch);

/* ------------------------------------------------- a centre's copy */

/*
 * With a training centre ([records] centre, centre.h; docs/INSTRUCTOR.md
 * "A centre's rigs together") the rigs share one set of people: the
 * centre's users, groups, members and courses, of which each rig keeps a
 * copy here, so that a login is checked on the rig even while the centre
 * cannot be reached.
 * - Up: every change made on the rig (the calls above; a wrong PIN's
 *   count and wait are the rig's own and stay here) is queued, in the
 *   same transaction as the change itself (the schema's triggers), with
 *   a random ID by which the centre takes it once. The centre's worker
 *   sends the queue in order (accounts_queue_head(), _arrived()).
 * - Down: once the rig's queue is empty, the centre's accounts replace
 *   the rig's (accounts_replace()): the centre's state wins every
 *   conflict (it takes the first add of a name, and drops what it cannot
 *   apply).
 */
#define ACCOUNTS_ID_LEN 32 /* a queued change's ID: hex digits */

/* A queued change: CH's texts point into the struct's own. */
struct accounts_queued {
	char id[ACCOUNTS_ID_LEN + 1];
	struct accounts_change ch;
	char name[ACCOUNTS_NAME_MAX + 1];
	char group[ACCOUNTS_NAME_MAX + 1];
	char pin[ACCOUNTS_HASH_MAX + 1];
	char course[ACCOUNTS_COURSE_MAX + 1];
};

/*
 * The centre at URL (NULL or "": none) these accounts are kept with.
 * With one: changes queued from now on; the first time with this URL,
 * every user, group, member and course queued too (the centre takes
 * those it lacks) and the copy's version forgotten (the database made if
 * missing). Without: nothing queued, the queue emptied (a database not
 * made yet is left so). 0; -EIO.
 */
int accounts_centre(struct accounts *a, const char *url);

/* The change queued first into *Q, how many are queued into *WAITING.
 * 0; -ENOENT (none, or no database); -EIO. */
int accounts_queue_head(struct accounts *a, struct accounts_queued *q,
			size_t *waiting);

/* The queued change ID taken by the centre: out of the queue. 0; -EIO. */
int accounts_queue_arrived(struct accounts *a, const char *id);

/* The version of the centre's accounts last copied here into OUT (""
 * none yet, or no database). 0; -EIO. */
int accounts_copy_version(struct accounts *a, char *out, size_t size);

/*
 * The centre's accounts at VERSION made these, in one transaction,
 * nothing of it queued: the N changes CH onto empty accounts, first
 * USER_ADD (each with its Argon2id string), then GROUP_ADD, GROUP_JOIN and
 * GROUP_ASSIGN. A user it lacks is removed; one it has keeps their count
 * of wrong PINs while their PIN is the same. 0; -EBUSY (changes of the
 * rig are queued still: nothing done, the copy waits for them to
 * arrive); -EINVAL (a change of another kind, a name or hash out of the
 * rules, a member or group whose user it lacks: nothing done); -EIO.
 */
int accounts_replace(struct accounts *a, const char *version,
		     const struct accounts_change *ch, size_t n);

#endif
