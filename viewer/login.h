/*
 * login.h - endoview's login screen: who is training at the rig
 * (docs/TRAINEE.md, "Who is training"), as a state machine of what the
 * trainee types and what endosimd says. loginview.h draws it, rigctl.h
 * carries its requests; pure: no window, no socket, no clock.
 *
 *   LOGIN_OFF  nobody is asked: the rig's accounts hold no trainee, or
 *              --no-login, or no daemon has answered yet (and a replay
 *              never asks); endoview as it always was;
 *   LOGIN_ASK  the form: a name, then a PIN shown as dots; the keyboard
 *              types into it and drives nothing;
 *   LOGIN_IN   a trainee trains at the rig: their name in the HUD; the C
 *              key logs them out, and the form asks again.
 *
 * What endosimd says (login_daemon(), from its status every second or a
 * reply) decides between them, so that a login or logout made elsewhere
 * (endoctl login, logout, another endoview) shows here too.
 *
 * In the form: a character typed goes into the field that has the focus
 * (the name up to ACCOUNTS_NAME_MAX bytes of UTF-8, the PIN up to
 * ACCOUNTS_PIN_MAX characters; control characters are not taken);
 * Backspace takes the last character back, Tab moves to the other field,
 * Enter on the name to the PIN and on the PIN sends the login (when both
 * are filled in), Esc empties the form. A refusal keeps the name, empties
 * the PIN and shows endosimd's words (a wrong name or PIN; the wait that
 * wrong PINs in a row earn). The PIN is wiped (explicit_bzero()) once
 * sent, or when the form empties or goes.
 *
 * One struct, no allocation; the main thread.
 */
#ifndef ENDOVIEW_LOGIN_H
#define ENDOVIEW_LOGIN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "session/accounts.h"

enum login_stage {
	LOGIN_OFF,
	LOGIN_ASK,
	LOGIN_IN,
};

enum login_field {
	LOGIN_NAME,
	LOGIN_PIN,
};

/* The form's keys besides the characters. */
enum login_key {
	LOGIN_BACKSPACE,
	LOGIN_TAB,
	LOGIN_ENTER,
	LOGIN_ESCAPE,
};

#define LOGIN_PIN_BYTES (4 * ACCOUNTS_PIN_MAX) /* UTF-8, without the NUL */

struct login {
	enum login_stage stage;
	enum login_field focus;
	bool never;      /* --no-login: the form is never shown */
	bool scripted;   /* --trainee with its PIN: send once the daemon
			    answers */
	bool answered;   /* the daemon has said who trains */
	char name[ACCOUNTS_NAME_MAX + 1];
	char pin[LOGIN_PIN_BYTES + 1];
	char trainee[ACCOUNTS_NAME_MAX + 1]; /* who trains ("": nobody) */
	char error[256]; /* the last refusal's words; "": none */
};

/*
 * NEVER: --no-login. NAME (NULL: none): --trainee, the name filled in;
 * with PIN (NULL: none, $ENDOSIM_PIN) the login is sent as soon as the
 * daemon answers (login_scripted()), without the form unless refused.
 */
void login_init(struct login *l, bool never, const char *name,
		const char *pin);

/* endosimd's answer: ASKS whether its accounts hold a trainee, TRAINEE
 * who trains at the rig ("": nobody). */
void login_daemon(struct login *l, bool asks, const char *trainee);

/* The character C (a Unicode code point) typed into the form. */
void login_type(struct login *l, uint32_t c);

/* KEY pressed in the form: true when the login is to be sent now (the
 * name and PIN in l; login_sent() after). */
bool login_key(struct login *l, enum login_key key);

/* Whether --trainee's login is to be sent now (once, after the daemon
 * first answered). */
bool login_scripted(struct login *l);

/* The login just sent was accepted (TRAINEE trains now) or refused in
 * WORDS; either wipes the PIN. */
void login_accepted(struct login *l, const char *trainee);
void login_refused(struct login *l, const char *words);

/* How many characters the PIN holds (the dots drawn). */
size_t login_pin_chars(const struct login *l);

/* What the screen says, one line, for tests (--print-state): "off",
 * "Ann trains", or the form's "asking: name 'Ann', PIN 4 characters,
 * focus PIN: wrong name or PIN". */
void login_said(const struct login *l, char *out, size_t size);

#endif
