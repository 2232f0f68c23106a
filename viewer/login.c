/* login.c - see login.h. */
#include "viewer/login.h"

#include <stdio.h>
#include <string.h>

/* The form emptied, the PIN wiped (not --trainee's before it is sent). */
static void empty(struct login *l)
{
	if (l->scripted) {
		return;
	}
	explicit_bzero(l->pin, sizeof(l->pin));
	l->name[0] = '\0';
	l->error[0] = '\0';
	l->focus = LOGIN_NAME;
}

void login_init(struct login *l, bool never, const char *name,
		const char *pin)
{
	memset(l, 0, sizeof(*l));
	l->never = never;
	snprintf(l->name, sizeof(l->name), "%s", name ? name : "");
	l->focus = *l->name ? LOGIN_PIN : LOGIN_NAME;
	if (name && pin) {
		snprintf(l->pin, sizeof(l->pin), "%s", pin);
		l->scripted = true;
	}
}

void login_daemon(struct login *l, bool asks, const char *trainee)
{
	l->answered = true;
	if (*trainee) {
		if (l->stage != LOGIN_IN || strcmp(l->trainee, trainee)) {
			empty(l);
		}
		snprintf(l->trainee, sizeof(l->trainee), "%s", trainee);
		l->stage = LOGIN_IN;
		return;
	}
	l->trainee[0] = '\0';
	if ((asks || *l->error) && !l->never) {
		if (l->stage == LOGIN_IN) {
			empty(l); /* after a logout: the next trainee's */
		}
		l->stage = LOGIN_ASK;
		return;
	}
	if (l->stage != LOGIN_OFF) {
		empty(l);
	}
	l->stage = LOGIN_OFF;
}

/* The field with the focus and its size. */
static char *field(struct login *l, size_t *size)
{
	*size = l->focus == LOGIN_NAME ? sizeof(l->name) : sizeof(l->pin);
	return l->focus == LOGIN_NAME ? l->name : l->pin;
}

/* C as UTF-8 into OUT (4 bytes): how many bytes, 0 for what is no
 * character to type (a control character, a surrogate, beyond Unicode). */
static size_t utf8(uint32_t c, char *out)
{
	if (c < 0x20 || (c >= 0x7f && c < 0xa0) ||
	    (c >= 0xd800 && c < 0xe000) || c > 0x10ffff) {
		return 0;
	}
	if (c < 0x80) {
		out[0] = (char)c;
		return 1;
	}
	if (c < 0x800) {
		out[0] = (char)(0xc0 | c >> 6);
		out[1] = (char)(0x80 | (c & 0x3f));
		return 2;
	}
	if (c < 0x10000) {
		out[0] = (char)(0xe0 | c >> 12);
		out[1] = (char)(0x80 | (c >> 6 & 0x3f));
		out[2] = (char)(0x80 | (c & 0x3f));
		return 3;
	}
	out[0] = (char)(0xf0 | c >> 18);
	out[1] = (char)(0x80 | (c >> 12 & 0x3f));
	out[2] = (char)(0x80 | (c >> 6 & 0x3f));
	out[3] = (char)(0x80 | (c & 0x3f));
	return 4;
}

/* The characters (not bytes) of the UTF-8 text S. */
static size_t chars(const char *s)
{
	size_t n = 0;

	for (; *s; s++) {
		n += ((unsigned char)*s & 0xc0) != 0x80;
	}
	return n;
}

void login_type(struct login *l, uint32_t c)
{
	char bytes[4];
	size_t n = utf8(c, bytes), size, len;
	char *f;

	if (l->stage != LOGIN_ASK || !n) {
		return;
	}
	f = field(l, &size);
	len = strlen(f);
	if (len + n >= size ||
	    (l->focus == LOGIN_PIN && chars(f) >= ACCOUNTS_PIN_MAX)) {
		return;
	}
	memcpy(f + len, bytes, n);
	f[len + n] = '\0';
}

/* The last character of the field with the focus taken back. */
static void backspace(struct login *l)
{
	size_t size, len;
	char *f = field(l, &size);

	len = strlen(f);
	while (len && ((unsigned char)f[len - 1] & 0xc0) == 0x80) {
		f[--len] = '\0';
	}
	if (len) {
		f[len - 1] = '\0';
	}
}

bool login_key(struct login *l, enum login_key key)
{
	if (l->stage != LOGIN_ASK) {
		return false;
	}
	switch (key) {
	case LOGIN_BACKSPACE:
		backspace(l);
		return false;
	case LOGIN_TAB:
		l->focus = l->focus == LOGIN_NAME ? LOGIN_PIN : LOGIN_NAME;
		return false;
	case LOGIN_ESCAPE:
		empty(l);
		return false;
	case LOGIN_ENTER:
		break;
	}
	if (l->focus == LOGIN_NAME || !*l->name) {
		l->focus = *l->name ? LOGIN_PIN : LOGIN_NAME;
		return false;
	}
	return *l->pin != '\0';
}

bool login_scripted(struct login *l)
{
	bool now = l->scripted && l->answered;

	l->scripted &= !now;
	return now;
}

void login_accepted(struct login *l, const char *trainee)
{
	empty(l);
	snprintf(l->trainee, sizeof(l->trainee), "%s", trainee);
	l->stage = LOGIN_IN;
}

void login_refused(struct login *l, const char *words)
{
	explicit_bzero(l->pin, sizeof(l->pin));
	snprintf(l->error, sizeof(l->error), "%s", words);
	l->focus = *l->name ? LOGIN_PIN : LOGIN_NAME;
	l->trainee[0] = '\0';
	l->stage = l->never ? LOGIN_OFF : LOGIN_ASK;
}

size_t login_pin_chars(const struct login *l)
{
	return chars(l->pin);
}

void login_said(const struct login *l, char *out, size_t size)
{
	switch (l->stage) {
	case LOGIN_OFF:
		snprintf(out, size, "off");
		break;
	case LOGIN_IN:
		snprintf(out, size, "%s trains", l->trainee);
		break;
	case LOGIN_ASK:
		snprintf(out, size, "asking: name '%s', PIN %zu characters, "
			 "focus %s%s%s", l->name, login_pin_chars(l),
			 l->focus == LOGIN_NAME ? "name" : "PIN",
			 *l->error ? ": " : "", l->error);
		break;
	}
}
