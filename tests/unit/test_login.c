/*
 * test_login.c - endoview's login screen as a state machine
 * (viewer/login.h): what endosimd says decides whether it asks; typing a
 * name and a PIN (UTF-8, control characters refused, each field's limit,
 * Backspace a whole character, Tab, Enter on each field, Esc); a refusal
 * keeps the name and empties the PIN, showing the daemon's words; an
 * acceptance; a logout asking again for the next trainee; --trainee's
 * login sent once, after the daemon first answered; --no-login never
 * asking; what the screen says for tests.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "viewer/login.h"

static void type(struct login *l, const char *ascii)
{
	for (; *ascii; ascii++) {
		login_type(l, (unsigned char)*ascii);
	}
}

static void said(const struct login *l, const char *want)
{
	char text[512];

	login_said(l, text, sizeof(text));
	assert_string_equal(text, want);
}

static void test_asks_as_the_daemon_says(void **state)
{
	struct login l;

	(void)state;
	login_init(&l, false, NULL, NULL);
	assert_int_equal(l.stage, LOGIN_OFF);
	type(&l, "Ann"); /* nothing asked yet: the keys drive, not type */
	assert_string_equal(l.name, "");
	login_daemon(&l, false, "");
	assert_int_equal(l.stage, LOGIN_OFF); /* no trainee's account */
	login_daemon(&l, true, "");
	assert_int_equal(l.stage, LOGIN_ASK);
	said(&l, "asking: name '', PIN 0 characters, focus name");
	/* a login made elsewhere (endoctl login): in, the form gone */
	type(&l, "Bo");
	login_daemon(&l, true, "Ann");
	assert_int_equal(l.stage, LOGIN_IN);
	assert_string_equal(l.trainee, "Ann");
	assert_string_equal(l.name, "");
	said(&l, "Ann trains");
	/* ... and a logout made elsewhere: asked again */
	login_daemon(&l, true, "");
	assert_int_equal(l.stage, LOGIN_ASK);
	assert_string_equal(l.trainee, "");
	/* no daemon (or its accounts gone): nothing asked */
	login_daemon(&l, false, "");
	assert_int_equal(l.stage, LOGIN_OFF);
}

static void test_typing(void **state)
{
	struct login l;

	(void)state;
	login_init(&l, false, NULL, NULL);
	login_daemon(&l, true, "");
	type(&l, "Zo");
	login_type(&l, 0xeb);    /* e with diaeresis: two bytes */
	login_type(&l, '\n');    /* control characters: not taken */
	login_type(&l, 0x1b);
	login_type(&l, 0x7f);
	login_type(&l, 0x85);
	login_type(&l, 0xd800);  /* a surrogate, and beyond Unicode */
	login_type(&l, 0x110000);
	assert_string_equal(l.name, "Zo\xc3\xab");
	assert_false(login_key(&l, LOGIN_BACKSPACE)); /* the whole character */
	assert_string_equal(l.name, "Zo");
	login_type(&l, 0x1f600); /* four bytes */
	assert_string_equal(l.name, "Zo\xf0\x9f\x98\x80");
	assert_false(login_key(&l, LOGIN_BACKSPACE));
	type(&l, "e D");
	assert_string_equal(l.name, "Zoe D");
	/* Enter on an empty PIN sends nothing; Tab and Enter move the focus */
	assert_false(login_key(&l, LOGIN_ENTER));
	assert_int_equal(l.focus, LOGIN_PIN);
	assert_false(login_key(&l, LOGIN_ENTER));
	type(&l, "48");
	login_type(&l, 0xe9);
	assert_int_equal(login_pin_chars(&l), 3);
	said(&l, "asking: name 'Zoe D', PIN 3 characters, focus PIN");
	assert_false(login_key(&l, LOGIN_TAB));
	assert_int_equal(l.focus, LOGIN_NAME);
	type(&l, "!");
	assert_false(login_key(&l, LOGIN_TAB));
	type(&l, "1");
	assert_string_equal(l.name, "Zoe D!");
	assert_string_equal(l.pin, "48\xc3\xa9" "1");
	assert_true(login_key(&l, LOGIN_ENTER)); /* on the PIN: send */
	/* Esc: the form empty, the focus on the name */
	assert_false(login_key(&l, LOGIN_ESCAPE));
	assert_string_equal(l.name, "");
	assert_string_equal(l.pin, "");
	assert_int_equal(l.focus, LOGIN_NAME);
	/* Enter with no name: the focus stays there */
	assert_false(login_key(&l, LOGIN_ENTER));
	assert_int_equal(l.focus, LOGIN_NAME);
}

static void test_limits(void **state)
{
	struct login l;

	(void)state;
	login_init(&l, false, NULL, NULL);
	login_daemon(&l, true, "");
	for (int k = 0; k < 200; k++) {
		login_type(&l, 0xeb);
	}
	assert_int_equal(strlen(l.name), ACCOUNTS_NAME_MAX - 1); /* 31 x 2 */
	login_key(&l, LOGIN_TAB);
	for (int k = 0; k < 200; k++) {
		login_type(&l, 0x1f600);
	}
	assert_int_equal(login_pin_chars(&l), ACCOUNTS_PIN_MAX);
	assert_int_equal(strlen(l.pin), 4 * ACCOUNTS_PIN_MAX);
	for (int k = 0; k < 200; k++) {
		login_key(&l, LOGIN_BACKSPACE);
	}
	assert_string_equal(l.pin, "");
	login_key(&l, LOGIN_BACKSPACE); /* nothing left: no harm */
	assert_string_equal(l.pin, "");
}

static void test_refused_then_accepted(void **state)
{
	struct login l;

	(void)state;
	login_init(&l, false, NULL, NULL);
	login_daemon(&l, true, "");
	type(&l, "Ann");
	assert_false(login_key(&l, LOGIN_ENTER));
	type(&l, "0000");
	assert_true(login_key(&l, LOGIN_ENTER));
	login_refused(&l, "wrong name or PIN");
	assert_int_equal(l.stage, LOGIN_ASK);
	assert_string_equal(l.name, "Ann");
	assert_string_equal(l.pin, "");
	assert_int_equal(l.focus, LOGIN_PIN);
	said(&l, "asking: name 'Ann', PIN 0 characters, focus PIN: wrong name "
	     "or PIN");
	/* the daemon says nothing new: the words stay */
	login_daemon(&l, true, "");
	assert_string_equal(l.error, "wrong name or PIN");
	type(&l, "4821");
	assert_true(login_key(&l, LOGIN_ENTER));
	login_refused(&l, "too many wrong PINs for Ann: try again in 4 s");
	said(&l, "asking: name 'Ann', PIN 0 characters, focus PIN: too many "
	     "wrong PINs for Ann: try again in 4 s");
	type(&l, "48213579");
	assert_true(login_key(&l, LOGIN_ENTER));
	login_accepted(&l, "Ann");
	assert_int_equal(l.stage, LOGIN_IN);
	assert_string_equal(l.pin, "");
	assert_string_equal(l.name, "");
	assert_string_equal(l.error, "");
	type(&l, "x"); /* in: the keys drive again */
	assert_string_equal(l.name, "");
	assert_false(login_key(&l, LOGIN_ENTER));
	/* C: she logs out; the form asks the next trainee, empty */
	login_daemon(&l, true, "");
	said(&l, "asking: name '', PIN 0 characters, focus name");
}

static void test_scripted(void **state)
{
	struct login l;

	(void)state;
	login_init(&l, false, "Ann", "48213579");
	assert_false(login_scripted(&l)); /* not before the daemon answers */
	login_daemon(&l, true, "Bo");     /* Bo forgot to log out */
	assert_string_equal(l.pin, "48213579"); /* kept for the login */
	assert_true(login_scripted(&l));
	assert_string_equal(l.name, "Ann");
	assert_false(login_scripted(&l)); /* once */
	login_refused(&l, "wrong name or PIN");
	assert_int_equal(l.stage, LOGIN_ASK);
	said(&l, "asking: name 'Ann', PIN 0 characters, focus PIN: wrong name "
	     "or PIN");

	/* without the PIN: the form, the name filled in, asking the PIN */
	login_init(&l, false, "Ann", NULL);
	login_daemon(&l, true, "");
	assert_false(login_scripted(&l));
	said(&l, "asking: name 'Ann', PIN 0 characters, focus PIN");

	/* no trainee's account: sent all the same, the refusal shown */
	login_init(&l, false, "Ann", "1234");
	login_daemon(&l, false, "");
	assert_true(login_scripted(&l));
	login_refused(&l, "wrong name or PIN");
	login_daemon(&l, false, "");
	assert_int_equal(l.stage, LOGIN_ASK); /* until Esc */
	login_key(&l, LOGIN_ESCAPE);
	login_daemon(&l, false, "");
	assert_int_equal(l.stage, LOGIN_OFF);
}

static void test_never(void **state)
{
	struct login l;

	(void)state;
	login_init(&l, true, NULL, NULL);
	login_daemon(&l, true, "");
	assert_int_equal(l.stage, LOGIN_OFF);
	said(&l, "off");
	login_daemon(&l, true, "Ann"); /* who trains is still shown */
	assert_int_equal(l.stage, LOGIN_IN);
	login_daemon(&l, true, "");
	assert_int_equal(l.stage, LOGIN_OFF);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_asks_as_the_daemon_says),
		cmocka_unit_test(test_typing),
		cmocka_unit_test(test_limits),
		cmocka_unit_test(test_refused_then_accepted),
		cmocka_unit_test(test_scripted),
		cmocka_unit_test(test_never),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
