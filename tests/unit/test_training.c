/*
 * test_training.c - who trains at the rig (control/training.h): a
 * session's trainee from the one named, the rig's trainee and the
 * starting login, with each refusal in words; a training login of a
 * trainee only, refused while another's session records; a logout
 * refused while a session records and to a trainee logged in as another;
 * a removed user no longer trains. Each refusal changes nothing.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "control/training.h"

static const struct accounts_user ann = { "Ann", ACCOUNTS_TRAINEE };
static const struct accounts_user bo = { "Bo", ACCOUNTS_TRAINEE };
static const struct accounts_user ives = { "Dr Ives", ACCOUNTS_INSTRUCTOR };
static const struct accounts_user ada = { "Ada", ACCOUNTS_ADMINISTRATOR };

static char why[256];

/* Why the last call refused holds WORDS. */
static void said(const char *words)
{
	if (!strstr(why, words)) {
		print_message("said: %s\n", why);
	}
	assert_non_null(strstr(why, words));
}

/* The trainee of a session started naming NAMED by LOGIN, expected to be
 * WANT (0) or refused with E. */
static void session(const struct training *t, const char *named,
		    const struct accounts_user *login, int e,
		    const char *want)
{
	char out[ACCOUNTS_NAME_MAX + 1] = "unchanged";

	why[0] = '\0';
	assert_int_equal(training_session(t, named, login, out, sizeof(out),
					  why, sizeof(why)), e);
	assert_string_equal(out, e ? "unchanged" : want);
}

static void test_session_trainee(void **state)
{
	struct training t = { .asks = true };

	(void)state;
	/* nobody trains: the one named, else the trainee's own login, else
	   nobody, as without accounts */
	session(&t, "Bo", NULL, 0, "Bo");
	session(&t, "", NULL, 0, "");
	session(&t, "", &ann, 0, "Ann");
	session(&t, "", &ives, 0, "");
	session(&t, "Bo", &ives, 0, "Bo");
	session(&t, "Bo", &ann, -EPERM, NULL);
	said("Bo's session: a trainee starts only their own (you are logged "
	     "in as Ann (trainee))");

	/* Ann trains: hers, whoever starts it without naming another */
	assert_int_equal(training_login(&t, &ann, NULL, why, sizeof(why)), 0);
	session(&t, "", NULL, 0, "Ann");
	session(&t, "", &ives, 0, "Ann");
	session(&t, "", &ada, 0, "Ann");
	session(&t, "Ann", NULL, 0, "Ann");
	session(&t, "", &ann, 0, "Ann");
	session(&t, "Bo", &ives, -EBUSY, NULL);
	said("Ann is training at the rig: a session of Bo needs Ann to log "
	     "out first");
	session(&t, "", &bo, -EPERM, NULL);
	said("Ann's session: a trainee starts only their own (you are logged "
	     "in as Bo (trainee))");
	session(&t, "Bo", &bo, -EBUSY, NULL);
	said("a session of Bo needs Ann to log out first");
	assert_string_equal(t.trainee, "Ann");
}

static void test_login(void **state)
{
	struct training t = { 0 };

	(void)state;
	assert_int_equal(training_login(&t, &ives, NULL, why, sizeof(why)),
			 -EPERM);
	said("Dr Ives is an instructor: only a trainee trains at the rig");
	assert_int_equal(training_login(&t, &ada, NULL, why, sizeof(why)),
			 -EPERM);
	said("Ada is an administrator");
	assert_string_equal(t.trainee, "");

	assert_int_equal(training_login(&t, &ann, NULL, why, sizeof(why)), 0);
	assert_string_equal(t.trainee, "Ann");
	/* another logs in: the rig's trainee changes (Ann forgot to log out) */
	assert_int_equal(training_login(&t, &bo, NULL, why, sizeof(why)), 0);
	assert_string_equal(t.trainee, "Bo");
	/* while Bo's session records: Bo again, not Ann */
	assert_int_equal(training_login(&t, &bo, "Bo", why, sizeof(why)), 0);
	assert_int_equal(training_login(&t, &ann, "Bo", why, sizeof(why)),
			 -EBUSY);
	said("a session of Bo is recording: another trainee logs in after "
	     "'session stop'");
	assert_int_equal(training_login(&t, &ann, "", why, sizeof(why)),
			 -EBUSY);
	said("a session is recording");
	assert_string_equal(t.trainee, "Bo");
}

static void test_logout(void **state)
{
	struct training t = { 0 };

	(void)state;
	/* nobody trains: a logout is no change, even while recording */
	assert_int_equal(training_logout(&t, NULL, "Cy", why, sizeof(why)), 0);
	assert_int_equal(training_login(&t, &ann, NULL, why, sizeof(why)), 0);
	assert_int_equal(training_logout(&t, &bo, NULL, why, sizeof(why)),
			 -EPERM);
	said("Ann is training at the rig: a trainee logs out only themself "
	     "(you are logged in as Bo (trainee))");
	assert_int_equal(training_logout(&t, &ann, "Ann", why, sizeof(why)),
			 -EBUSY);
	said("a session of Ann is recording: the trainee logs out after "
	     "'session stop'");
	assert_string_equal(t.trainee, "Ann");
	assert_int_equal(training_logout(&t, &ann, NULL, why, sizeof(why)), 0);
	assert_string_equal(t.trainee, "");
	/* the staff (not logged in) and an instructor log out whoever trains */
	assert_int_equal(training_login(&t, &bo, NULL, why, sizeof(why)), 0);
	assert_int_equal(training_logout(&t, NULL, NULL, why, sizeof(why)), 0);
	assert_int_equal(training_login(&t, &bo, NULL, why, sizeof(why)), 0);
	assert_int_equal(training_logout(&t, &ives, NULL, why, sizeof(why)), 0);
	assert_string_equal(t.trainee, "");
}

static void test_forget(void **state)
{
	struct training t = { 0 };

	(void)state;
	assert_int_equal(training_login(&t, &ann, NULL, why, sizeof(why)), 0);
	training_forget(&t, "Bo");
	assert_string_equal(t.trainee, "Ann");
	training_forget(&t, "Ann");
	assert_string_equal(t.trainee, "");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_session_trainee),
		cmocka_unit_test(test_login),
		cmocka_unit_test(test_logout),
		cmocka_unit_test(test_forget),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
