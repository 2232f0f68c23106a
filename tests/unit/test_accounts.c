/*
 * test_accounts.c - who sees what (accounts.h): users, their PINs as
 * Argon2id hashes (the PIN nowhere in the file), a login with the right
 * and a wrong PIN, the wait that wrong PINs in a row earn and that a right
 * PIN clears, an unknown name refused in the same words, the trainees
 * each role sees, groups and their courses, and every refusal in words
 * that changes nothing. Who changes what (accounts_may()): an instructor
 * in the groups they manage and never beyond them.
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

	assert_int_equal(accounts_user_add(a, "Ann", ACCOUNTS_TRAINEE, "1111"),
			 0);
	assert_int_equal(accounts_user_add(a, "Cy", ACCOUNTS_TRAINEE, "3333"),
			 0);
	assert_int_equal(accounts_user_add(a, "Di", ACCOUNTS_TRAINEE, "4444"),
			 0);
	assert_int_equal(accounts_user_add(a, "Dr Ives", ACCOUNTS_INSTRUCTOR,
					   "5555"), 0);
	assert_int_equal(accounts_user_add(a, "Dr Jay", ACCOUNTS_INSTRUCTOR,
					   "6666"), 0);
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

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_users, setup, teardown),
		cmocka_unit_test_setup_teardown(test_wrong_pins, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_groups, setup, teardown),
		cmocka_unit_test_setup_teardown(test_who_changes, setup,
						teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
