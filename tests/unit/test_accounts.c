/*
 * test_accounts.c - who sees what (accounts.h): users, their PINs as
 * Argon2id hashes (the PIN nowhere in the file), a login with the right
 * and a wrong PIN, the wait that wrong PINs in a row earn and that a right
 * PIN clears, an unknown name refused in the same words, the trainees
 * each role sees, groups and their courses, and every refusal in words
 * that changes nothing. Who changes what (accounts_may()): an instructor
 * in the groups they manage and never beyond them. A centre's copy: each
 * change queued in order with the change itself (a wrong PIN's count
 * not), everything queued the first time with a centre, nothing without
 * one; the centre's accounts replacing the rig's only once its queue is
 * empty, queueing nothing, keeping a wrong PINs' count; a database of the
 * first schema opened by this one, its users intact.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "session/accounts.h"

struct fixture {
	char dir[64];
	char path[128];
	struct accounts *a;
};

static int setup(void **state)
{
	struct fixture *f = calloc(1, sizeof(*f));

	snprintf(f->dir, sizeof(f->dir), "/tmp/test_accounts.XXXXXX");
	assert_non_null(mkdtemp(f->dir));
	snprintf(f->path, sizeof(f->path), "%s/accounts.sqlite", f->dir);
	f->a = accounts_create(f->path);
	assert_non_null(f->a);
	*state = f;
	return 0;
}

static int teardown(void **state)
{
	struct fixture *f = *state;

	accounts_destroy(f->a);
	unlink(f->path);
	rmdir(f->dir);
	free(f);
	return 0;
}

static void said(const struct accounts *a, const char *words)
{
	if (!strstr(accounts_error(a), words)) {
		print_message("said: %s\n", accounts_error(a));
	}
	assert_non_null(strstr(accounts_error(a), words));
}

/* Whether the file at PATH holds the bytes S. */
static bool file_holds(const char *path, const char *s)
{
	FILE *fp = fopen(path, "rb");
	char buf[1 << 16];
	size_t n = fp ? fread(buf, 1, sizeof(buf), fp) : 0;

	if (fp) {
		fclose(fp);
	}
	return memmem(buf, n, s, strlen(s)) != NULL;
}

static void test_users(void **state)
{
	struct fixture *f = *state;
	struct accounts_user *u, who;
	double wait;
	size_t n;

	assert_int_equal(accounts_users(f->a, &u, &n), 0); /* none yet */
	assert_int_equal(n, 0);
	assert_int_equal(accounts_user_add(f->a, "Ann", ACCOUNTS_TRAINEE,
					   "482913"), 0);
	assert_int_equal(accounts_user_add(f->a, "Robert'); DROP TABLE users;"
					   "--", ACCOUNTS_INSTRUCTOR, "7777"),
			 0);
	assert_int_equal(accounts_user_add(f->a, "Ann", ACCOUNTS_TRAINEE,
					   "1111"), -EEXIST);
	said(f->a, "there is a user Ann already");
	assert_int_equal(accounts_user_add(f->a, "Bo", ACCOUNTS_TRAINEE,
					   "123"), -EINVAL);
	said(f->a, "a PIN: 4 to 64 characters");
	assert_int_equal(accounts_user_add(f->a, "Bo\n", ACCOUNTS_TRAINEE,
					   "1234"), -EINVAL);
	said(f->a, "a user's name");
	assert_int_equal(accounts_users(f->a, &u, &n), 0);
	assert_int_equal(n, 2);
	assert_string_equal(u[0].name, "Ann");
	assert_int_equal(u[0].role, ACCOUNTS_TRAINEE);
	assert_int_equal(u[1].role, ACCOUNTS_INSTRUCTOR);
	free(u);
	/* the PINs are hashed: not in the file, Argon2id's strings are */
	assert_false(file_holds(f->path, "482913"));
	assert_true(file_holds(f->path, "$argon2id$"));

	assert_int_equal(accounts_login(f->a, "Ann", "482913", 1000, &who,
					&wait), 0);
	assert_string_equal(who.name, "Ann");
	assert_int_equal(who.role, ACCOUNTS_TRAINEE);
	assert_int_equal(accounts_login(f->a, "Robert'); DROP TABLE users;--",
					"7777", 1000, &who, &wait), 0);
	assert_int_equal(who.role, ACCOUNTS_INSTRUCTOR);

	assert_int_equal(accounts_user_pin(f->a, "Ann", "5555"), 0);
	assert_int_equal(accounts_login(f->a, "Ann", "482913", 1000, &who,
					&wait), -EACCES);
	assert_int_equal(accounts_login(f->a, "Ann", "5555", 1000, &who,
					&wait), 0);
	assert_int_equal(accounts_user_pin(f->a, "Nobody", "5555"), -ENOENT);
	said(f->a, "no user Nobody");
	assert_int_equal(accounts_user_remove(f->a, "Ann"), 0);
	assert_int_equal(accounts_user_remove(f->a, "Ann"), -ENOENT);
	assert_int_equal(accounts_login(f->a, "Ann", "5555", 1000, &who,
					&wait), -EACCES);
}

static void test_wrong_pins(void **state)
{
	struct fixture *f = *state;
	struct accounts_user who;
	double wait = -1, t = 5000;

	assert_int_equal(accounts_user_add(f->a, "Ann", ACCOUNTS_TRAINEE,
					   "482913"), 0);
	for (int i = 0; i < ACCOUNTS_FREE_TRIES - 1; i++) {
		assert_int_equal(accounts_login(f->a, "Ann", "000000", t, &who,
						&wait), -EACCES);
		assert_true(wait == 0); /* a few tries are free */
		said(f->a, "wrong name or PIN");
	}
	assert_int_equal(accounts_login(f->a, "Ann", "000000", t, &who,
					&wait), -EACCES);
	assert_true(wait == 1.0);
	/* while she waits even the right PIN is refused, unlooked at */
	assert_int_equal(accounts_login(f->a, "Ann", "482913", t + 0.5, &who,
					&wait), -EAGAIN);
	assert_true(wait > 0.49 && wait < 0.51);
	said(f->a, "too many wrong PINs for Ann: try again in 1 s");
	/* the wait grows with each further wrong PIN */
	assert_int_equal(accounts_login(f->a, "Ann", "000000", t + 1.5, &who,
					&wait), -EACCES);
	assert_true(wait == 2.0);
	assert_int_equal(accounts_login(f->a, "Ann", "000000", t + 4, &who,
					&wait), -EACCES);
	assert_true(wait == 4.0);
	assert_int_equal(accounts_login(f->a, "Ann", "482913", t + 7.9, &who,
					&wait), -EAGAIN);
	/* after it, the right PIN: in, and the count cleared */
	assert_int_equal(accounts_login(f->a, "Ann", "482913", t + 8.1, &who,
					&wait), 0);
	assert_int_equal(accounts_login(f->a, "Ann", "000000", t + 9, &who,
					&wait), -EACCES);
	assert_true(wait == 0);
	/* an unknown name: the same words, no wait to tell it apart */
	assert_int_equal(accounts_login(f->a, "Zed", "000000", t, &who,
					&wait), -EACCES);
	said(f->a, "wrong name or PIN");
}

/* Whether U sees exactly the trainees WANT ("a\nb"; NULL: all). */
static void sees(struct accounts *a, const char *name,
		 enum accounts_role role, const char *want)
{
	struct accounts_user u = { .role = role };
	char *names;
	bool all;

	snprintf(u.name, sizeof(u.name), "%s", name);
	assert_int_equal(accounts_seen(a, &u, &names, &all), 0);
	assert_int_equal(all, want == NULL);
	assert_string_equal(names, want ? want : "");
	free(names);
}

static void test_groups(void **state)
{
	struct fixture *f = *state;
	struct accounts_group *g;
	size_t n;

	assert_int_equal(accounts_user_add(f->a, "Ann", ACCOUNTS_TRAINEE,
					   "1111"), 0);
	assert_int_equal(accounts_user_add(f->a, "Bo", ACCOUNTS_TRAINEE,
					   "2222"), 0);
	assert_int_equal(accounts_user_add(f->a, "Cy", ACCOUNTS_TRAINEE,
					   "3333"), 0);
	assert_int_equal(accounts_user_add(f->a, "Dr Ives", ACCOUNTS_INSTRUCTOR,
					   "4444"), 0);
	assert_int_equal(accounts_user_add(f->a, "Dr Jay", ACCOUNTS_INSTRUCTOR,
					   "5555"), 0);
	assert_int_equal(accounts_group_add(f->a, "2026", "Ann"), -ENOENT);
	said(f->a, "no instructor Ann");
	assert_int_equal(accounts_group_add(f->a, "2026", "Dr Ives"), 0);
	assert_int_equal(accounts_group_add(f->a, "2026", "Dr Jay"), -EEXIST);
	assert_int_equal(accounts_group_add(f->a, "2027", "Dr Jay"), 0);
	assert_int_equal(accounts_group_member(f->a, "2026", "Bo", true), 0);
	assert_int_equal(accounts_group_member(f->a, "2026", "Ann", true), 0);
	assert_int_equal(accounts_group_member(f->a, "2026", "Ann", true), 0);
	assert_int_equal(accounts_group_member(f->a, "2027", "Cy", true), 0);
	assert_int_equal(accounts_group_member(f->a, "2027", "Dr Ives", true),
			 -ENOENT);
	said(f->a, "no trainee Dr Ives");
	assert_int_equal(accounts_group_member(f->a, "1999", "Ann", true),
			 -ENOENT);
	said(f->a, "no group 1999");
	assert_int_equal(accounts_group_course(f->a, "2026", "basic.course",
					       true), 0);

	sees(f->a, "Ann", ACCOUNTS_TRAINEE, "Ann");
	sees(f->a, "Dr Ives", ACCOUNTS_INSTRUCTOR, "Ann\nBo");
	sees(f->a, "Dr Jay", ACCOUNTS_INSTRUCTOR, "Cy");
	sees(f->a, "root", ACCOUNTS_ADMINISTRATOR, NULL);
	assert_true(accounts_among("Ann\nBo", "Bo"));
	assert_true(accounts_among("Ann\nBo", "Ann"));
	assert_false(accounts_among("Ann\nBo", "An"));
	assert_false(accounts_among("Ann\nBo", "Ann\nBo\n"));
	assert_false(accounts_among("", ""));

	assert_int_equal(accounts_user_remove(f->a, "Dr Ives"), -EBUSY);
	said(f->a, "Dr Ives manages a group");
	assert_int_equal(accounts_group_member(f->a, "2026", "Bo", false), 0);
	sees(f->a, "Dr Ives", ACCOUNTS_INSTRUCTOR, "Ann");
	assert_int_equal(accounts_user_remove(f->a, "Ann"), 0);
	sees(f->a, "Dr Ives", ACCOUNTS_INSTRUCTOR, "");

	assert_int_equal(accounts_groups(f->a, NULL, &g, &n), 0);
	assert_int_equal(n, 2);
	assert_string_equal(g[0].name, "2026");
	assert_string_equal(g[0].instructor, "Dr Ives");
	assert_string_equal(g[0].courses, "basic.course");
	assert_string_equal(g[1].trainees, "Cy");
	accounts_groups_free(g, n);
	assert_int_equal(accounts_group_remove(f->a, "2026"), 0);
	assert_int_equal(accounts_group_remove(f->a, "2026"), -ENOENT);
	assert_int_equal(accounts_user_remove(f->a, "Dr Ives"), 0);
}

/* User NAME of ROLE added with PIN. */
static void add(struct accounts *a, const char *name, enum accounts_role role,
		const char *pin)
{
	assert_int_equal(accounts_user_add(a, name, role, pin), 0);
}

/* The change OP of NAME in GROUP (COURSE, ROLE) that U may make: E. */
static void may(struct accounts *a, const struct accounts_user *u,
		enum accounts_op op, const char *name, const char *group,
		enum accounts_role role, int e, const char *words)
{
	struct accounts_change ch = { .op = op, .name = name, .role = role,
				      .pin = "", .group = group,
				      .course = "basic.course" };

	assert_int_equal(accounts_may(a, u, &ch), e);
	if (words) {
		said(a, words);
	}
}

/* The trainees of group G ("a\nb"). */
static void members_are(struct accounts *a, const char *g, const char *want)
{
	struct accounts_group *all;
	size_t n;
	bool found = false;

	assert_int_equal(accounts_groups(a, NULL, &all, &n), 0);
	for (size_t i = 0; i < n; i++) {
		if (!strcmp(all[i].name, g)) {
			assert_string_equal(all[i].trainees, want);
			found = true;
		}
	}
	accounts_groups_free(all, n);
	assert_true(found);
}

static void test_who_changes(void **state)
{
	struct fixture *f = *state;
	struct accounts_user ives = { "Dr Ives", ACCOUNTS_INSTRUCTOR },
			     ann = { "Ann", ACCOUNTS_TRAINEE },
			     ada = { "Ada", ACCOUNTS_ADMINISTRATOR };
	struct accounts *a = f->a;

	add(a, "Ann", ACCOUNTS_TRAINEE, "1111");
	add(a, "Cy", ACCOUNTS_TRAINEE, "3333");
	add(a, "Di", ACCOUNTS_TRAINEE, "4444");
	add(a, "Dr Ives", ACCOUNTS_INSTRUCTOR, "5555");
	add(a, "Dr Jay", ACCOUNTS_INSTRUCTOR, "6666");
	assert_int_equal(accounts_group_add(a, "2026", "Dr Ives"), 0);
	assert_int_equal(accounts_group_add(a, "2027", "Dr Jay"), 0);
	assert_int_equal(accounts_group_member(a, "2026", "Ann", true), 0);
	assert_int_equal(accounts_group_member(a, "2027", "Cy", true), 0);

	/* an instructor in the groups they manage */
	may(a, &ives, ACCOUNTS_USER_ADD, "Eve", "", ACCOUNTS_TRAINEE, 0, NULL);
	may(a, &ives, ACCOUNTS_GROUP_JOIN, "Di", "2026", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_GROUP_JOIN, "Ann", "2026", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_GROUP_LEAVE, "Ann", "2026", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_GROUP_ASSIGN, "", "2026", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_GROUP_UNASSIGN, "", "2026", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_USER_PIN, "Ann", "", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_USER_PIN, "Dr Ives", "", 0, 0, NULL);
	may(a, &ives, ACCOUNTS_GROUP_JOIN, "Ann", "1999", 0, 0, NULL);
	/* and never beyond them */
	may(a, &ives, ACCOUNTS_USER_ADD, "Eve", "", ACCOUNTS_INSTRUCTOR,
	    -EPERM, "an instructor adds trainees only");
	may(a, &ives, ACCOUNTS_USER_ADD, "Eve", "", ACCOUNTS_ADMINISTRATOR,
	    -EPERM, "an instructor adds trainees only");
	may(a, &ives, ACCOUNTS_USER_REMOVE, "Ann", "", 0, -EPERM,
	    "only an administrator removes a user");
	may(a, &ives, ACCOUNTS_GROUP_ADD, "Dr Ives", "2028", 0, -EPERM,
	    "only an administrator makes or removes a group");
	may(a, &ives, ACCOUNTS_GROUP_REMOVE, "", "2026", 0, -EPERM,
	    "only an administrator makes or removes a group");
	for (enum accounts_op op = ACCOUNTS_GROUP_JOIN;
	     op <= ACCOUNTS_GROUP_UNASSIGN; op++) {
		may(a, &ives, op, "Di", "2027", 0, -EPERM, "group 2027 is Dr "
		    "Jay's: an instructor changes only the groups they manage");
	}
	may(a, &ives, ACCOUNTS_GROUP_JOIN, "Cy", "2026", 0, -EPERM,
	    "Cy is a trainee of group 2027, Dr Jay's: an administrator moves");
	may(a, &ives, ACCOUNTS_USER_PIN, "Cy", "", 0, -EPERM,
	    "Cy's PIN: an instructor sets the PINs of their groups' trainees");
	may(a, &ives, ACCOUNTS_USER_PIN, "Dr Jay", "", 0, -EPERM, "PIN");
	/* a trainee: their own PIN; an administrator: anything */
	may(a, &ann, ACCOUNTS_USER_PIN, "Ann", "", 0, 0, NULL);
	may(a, &ann, ACCOUNTS_GROUP_LEAVE, "Ann", "2026", 0, -EPERM,
	    "only an administrator, or an instructor in the groups they "
	    "manage, changes the accounts");
	may(a, &ann, ACCOUNTS_USER_ADD, "Eve", "", ACCOUNTS_TRAINEE, -EPERM,
	    "only an administrator");
	may(a, &ada, ACCOUNTS_USER_REMOVE, "Dr Jay", "", 0, 0, NULL);
	may(a, &ada, ACCOUNTS_USER_ADD, "Eve", "", ACCOUNTS_ADMINISTRATOR, 0,
	    NULL);
	/* a rule judges: it changes nothing */
	members_are(a, "2026", "Ann");
	members_are(a, "2027", "Cy");
	assert_string_equal(accounts_op_name(ACCOUNTS_GROUP_UNASSIGN),
			    "group_unassign");
}

/* The changes queued, as "op name group course" lines, each taken. */
static void queued_are(struct accounts *a, const char *want)
{
	char got[1024] = "";
	struct accounts_queued q;
	size_t waiting, at = 0, before = SIZE_MAX;

	while (accounts_queue_head(a, &q, &waiting) == 0) {
		assert_true(waiting < before); /* one fewer each time */
		before = waiting;
		assert_int_equal(strlen(q.id), ACCOUNTS_ID_LEN);
		at += (size_t)snprintf(got + at, sizeof(got) - at, "%s%s %s %s"
				       " %s", at ? "\n" : "",
				       accounts_op_name(q.ch.op), q.ch.name,
				       q.ch.group, q.ch.course);
		if (q.ch.op == ACCOUNTS_USER_ADD ||
		    q.ch.op == ACCOUNTS_USER_PIN) {
			assert_memory_equal(q.ch.pin, "$argon2id$", 10);
		}
		assert_int_equal(accounts_queue_arrived(a, q.id), 0);
	}
	assert_string_equal(got, want);
}

static void test_centre_queue(void **state)
{
	struct fixture *f = *state;
	struct accounts *a = f->a;
	struct accounts_queued q;
	struct accounts_user who;
	char version[32];
	size_t waiting;
	double wait;

	/* without a centre: nothing queued */
	assert_int_equal(accounts_centre(a, NULL), 0);
	assert_int_equal(access(f->path, F_OK), -1); /* nor made */
	add(a, "Ann", ACCOUNTS_TRAINEE, "1111");
	add(a, "Dr Ives", ACCOUNTS_INSTRUCTOR, "5555");
	assert_int_equal(accounts_group_add(a, "2026", "Dr Ives"), 0);
	assert_int_equal(accounts_group_member(a, "2026", "Ann", true), 0);
	assert_int_equal(accounts_queue_head(a, &q, &waiting), -ENOENT);

	/* a centre: first everything, then each change as made */
	assert_int_equal(accounts_centre(a, "postgresql:///c1"), 0);
	assert_int_equal(accounts_copy_version(a, version, sizeof(version)), 0);
	assert_string_equal(version, "");
	add(a, "Bo", ACCOUNTS_TRAINEE, "2222");
	assert_int_equal(accounts_group_member(a, "2026", "Bo", true), 0);
	assert_int_equal(accounts_group_member(a, "2026", "Bo", true), 0);
	assert_int_equal(accounts_group_course(a, "2026", "basic.course", true),
			 0);
	assert_int_equal(accounts_user_pin(a, "Ann", "1112"), 0);
	/* a wrong PIN's count is the rig's own */
	assert_int_equal(accounts_login(a, "Ann", "0000", 100, &who, &wait),
			 -EACCES);
	assert_int_equal(accounts_group_member(a, "2026", "Bo", false), 0);
	assert_int_equal(accounts_group_course(a, "2026", "basic.course",
					       false), 0);
	queued_are(a, "user_add Ann  \nuser_add Dr Ives  \n"
		   "group_add Dr Ives 2026 \ngroup_join Ann 2026 \n"
		   "user_add Bo  \ngroup_join Bo 2026 \n"
		   "group_assign  2026 basic.course\nuser_pin Ann  \n"
		   "group_leave Bo 2026 \ngroup_unassign  2026 basic.course");
	/* a removal: the user's memberships go with it at the centre too */
	assert_int_equal(accounts_group_member(a, "2026", "Bo", true), 0);
	assert_int_equal(accounts_user_remove(a, "Bo"), 0);
	assert_int_equal(accounts_group_remove(a, "2026"), 0);
	queued_are(a, "group_join Bo 2026 \nuser_remove Bo  \n"
		   "group_remove  2026 ");
	/* the same centre again: nothing queued anew; another: everything */
	assert_int_equal(accounts_centre(a, "postgresql:///c1"), 0);
	assert_int_equal(accounts_queue_head(a, &q, &waiting), -ENOENT);
	assert_int_equal(accounts_centre(a, "postgresql:///c2"), 0);
	queued_are(a, "user_add Ann  \nuser_add Dr Ives  ");
	/* none: queueing off, the queue emptied */
	assert_int_equal(accounts_user_pin(a, "Ann", "1113"), 0);
	assert_int_equal(accounts_centre(a, ""), 0);
	assert_int_equal(accounts_queue_head(a, &q, &waiting), -ENOENT);
	assert_int_equal(accounts_user_pin(a, "Ann", "1114"), 0);
	assert_int_equal(accounts_queue_head(a, &q, &waiting), -ENOENT);
}

/* The Argon2id string of NAME's PIN in the database at PATH into OUT. */
static void hash_of(const char *path, const char *name, char *out,
		    size_t size)
{
	sqlite3_stmt *st;
	sqlite3 *db;

	assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
	assert_int_equal(sqlite3_prepare_v2(db, "SELECT pin FROM users WHERE "
					    "name = ?", -1, &st, NULL),
			 SQLITE_OK);
	sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
	assert_int_equal(sqlite3_step(st), SQLITE_ROW);
	snprintf(out, size, "%s", sqlite3_column_text(st, 0));
	sqlite3_finalize(st);
	sqlite3_close(db);
}

static void test_centre_copy(void **state)
{
	struct fixture *f = *state;
	struct accounts *a = f->a;
	char ann[128], bo[128], version[32];
	struct accounts_user who, *u;
	struct accounts_queued q;
	size_t waiting, n;
	double wait;

	add(a, "Ann", ACCOUNTS_TRAINEE, "1111");
	add(a, "Bo", ACCOUNTS_TRAINEE, "2222");
	add(a, "Zed", ACCOUNTS_TRAINEE, "9999");
	hash_of(f->path, "Ann", ann, sizeof(ann));
	hash_of(f->path, "Bo", bo, sizeof(bo));
	assert_int_equal(accounts_centre(a, "postgresql:///c1"), 0);
	/* three wrong PINs of Ann: she waits */
	for (int i = 0; i < 3; i++) {
		accounts_login(a, "Ann", "0000", 100, &who, &wait);
	}
	assert_true(wait > 0);

	/* the centre's: Ann as she was, Bo a new PIN and an instructor now,
	 * Cy from another rig, Zed no more; a group of Ann and Cy */
	const struct accounts_change copy[] = {
		{ ACCOUNTS_USER_ADD, "Ann", ACCOUNTS_TRAINEE, ann, "", "" },
		{ ACCOUNTS_USER_ADD, "Bo", ACCOUNTS_INSTRUCTOR, ann, "", "" },
		{ ACCOUNTS_USER_ADD, "Cy", ACCOUNTS_TRAINEE, bo, "", "" },
		{ ACCOUNTS_GROUP_ADD, "Bo", 0, "", "2026", "" },
		{ ACCOUNTS_GROUP_JOIN, "Ann", 0, "", "2026", "" },
		{ ACCOUNTS_GROUP_JOIN, "Cy", 0, "", "2026", "" },
		{ ACCOUNTS_GROUP_ASSIGN, "", 0, "", "2026", "basic.course" },
	};
	/* not while the rig's own changes wait */
	assert_int_equal(accounts_replace(a, "7", copy, 7), -EBUSY);
	said(a, "3 changes of the rig's accounts wait for the centre");
	assert_int_equal(accounts_copy_version(a, version, sizeof(version)), 0);
	assert_string_equal(version, "");
	queued_are(a, "user_add Ann  \nuser_add Bo  \nuser_add Zed  ");
	assert_int_equal(accounts_replace(a, "7", copy, 7), 0);
	assert_int_equal(accounts_copy_version(a, version, sizeof(version)), 0);
	assert_string_equal(version, "7");
	assert_int_equal(accounts_queue_head(a, &q, &waiting), -ENOENT);

	assert_int_equal(accounts_users(a, &u, &n), 0);
	assert_int_equal(n, 3);
	assert_string_equal(u[0].name, "Ann");
	assert_string_equal(u[1].name, "Bo");
	assert_int_equal(u[1].role, ACCOUNTS_INSTRUCTOR);
	assert_string_equal(u[2].name, "Cy");
	free(u);
	members_are(a, "2026", "Ann\nCy");
	/* Ann's PIN the same: she waits still, her count kept (a fourth
	 * wrong PIN earns 2 s); Bo's new; Cy's Bo's old */
	assert_int_equal(accounts_login(a, "Ann", "1111", 100.5, &who, &wait),
			 -EAGAIN);
	assert_int_equal(accounts_login(a, "Ann", "0000", 101.5, &who, &wait),
			 -EACCES);
	assert_true(wait == 2.0);
	assert_int_equal(accounts_login(a, "Bo", "1111", 100, &who, &wait), 0);
	assert_int_equal(who.role, ACCOUNTS_INSTRUCTOR);
	assert_int_equal(accounts_login(a, "Cy", "2222", 100, &who, &wait), 0);
	assert_int_equal(accounts_login(a, "Zed", "9999", 100, &who, &wait),
			 -EACCES);

	/* a copy out of the rules: refused whole, nothing changed */
	const struct accounts_change bad[] = {
		{ ACCOUNTS_USER_ADD, "Di", ACCOUNTS_TRAINEE, ann, "", "" },
		{ ACCOUNTS_USER_ADD, "Eve", ACCOUNTS_TRAINEE, "1234", "", "" },
	};
	assert_int_equal(accounts_replace(a, "8", bad, 2), -EINVAL);
	said(a, "Eve's PIN: not an Argon2id string");
	const struct accounts_change orphan[] = {
		{ ACCOUNTS_GROUP_JOIN, "Ann", 0, "", "2029", "" },
	};
	assert_int_equal(accounts_replace(a, "8", orphan, 1), -EINVAL);
	said(a, "group_join Ann in 2029");
	assert_int_equal(accounts_copy_version(a, version, sizeof(version)), 0);
	assert_string_equal(version, "7");
	members_are(a, "2026", "Ann\nCy");
	assert_int_equal(accounts_queue_head(a, &q, &waiting), -ENOENT);
}

/* A database of the first schema, with Ann in it, opened by this one. */
static void test_migration(void **state)
{
	struct fixture *f = *state;
	struct accounts_user who;
	struct accounts_queued q;
	char hash[128];
	size_t waiting;
	double wait;
	sqlite3 *db;

	/* Ann's hash made by this schema, then the file made by the first */
	add(f->a, "Ann", ACCOUNTS_TRAINEE, "1111");
	hash_of(f->path, "Ann", hash, sizeof(hash));
	unlink(f->path);
	assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
	assert_int_equal(sqlite3_exec(db, "CREATE TABLE users (name TEXT "
		"PRIMARY KEY, role TEXT NOT NULL CHECK (role IN ('trainee', "
		"'instructor', 'administrator')), pin TEXT NOT NULL, failures "
		"INTEGER NOT NULL DEFAULT 0, wait_until REAL NOT NULL "
		"DEFAULT 0);"
		"CREATE TABLE groups (name TEXT PRIMARY KEY, instructor TEXT "
		"NOT NULL REFERENCES users(name));"
		"CREATE TABLE members (group_name TEXT NOT NULL REFERENCES "
		"groups(name) ON DELETE CASCADE, trainee TEXT NOT NULL "
		"REFERENCES users(name) ON DELETE CASCADE, PRIMARY KEY "
		"(group_name, trainee));"
		"CREATE TABLE courses (group_name TEXT NOT NULL REFERENCES "
		"groups(name) ON DELETE CASCADE, course TEXT NOT NULL, PRIMARY "
		"KEY (group_name, course));"
		"PRAGMA user_version = 1;", NULL, NULL, NULL), SQLITE_OK);
	sqlite3_stmt *st;
	assert_int_equal(sqlite3_prepare_v2(db, "INSERT INTO users (name, "
					    "role, pin) VALUES ('Ann', "
					    "'trainee', ?)", -1, &st, NULL),
			 SQLITE_OK);
	sqlite3_bind_text(st, 1, hash, -1, SQLITE_STATIC);
	assert_int_equal(sqlite3_step(st), SQLITE_DONE);
	sqlite3_finalize(st);
	sqlite3_close(db);

	assert_int_equal(accounts_login(f->a, "Ann", "1111", 100, &who, &wait),
			 0);
	assert_int_equal(accounts_centre(f->a, "postgresql:///c1"), 0);
	assert_int_equal(accounts_queue_head(f->a, &q, &waiting), 0);
	assert_string_equal(q.ch.name, "Ann");
	assert_string_equal(q.ch.pin, hash);
	assert_int_equal(waiting, 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_users, setup, teardown),
		cmocka_unit_test_setup_teardown(test_wrong_pins, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_groups, setup, teardown),
		cmocka_unit_test_setup_teardown(test_who_changes, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_centre_queue, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_centre_copy, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_migration, setup,
						teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
