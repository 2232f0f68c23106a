/* training.c - see training.h. */
#include "control/training.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

int training_session(const struct training *t, const char *named,
		     const struct accounts_user *login, char *out,
		     size_t size, char *why, size_t why_size)
{
	bool trainee = login && login->role == ACCOUNTS_TRAINEE;
	const char *who = *named     ? named :
			  *t->trainee ? t->trainee :
			  trainee     ? login->name : "";

	if (*t->trainee && strcmp(who, t->trainee)) {
		snprintf(why, why_size, "%s is training at the rig: a session "
			 "of %s needs %s to log out first (endoview's C key, "
			 "or endoctl logout)", t->trainee, who, t->trainee);
		return -EBUSY;
	}
	if (trainee && strcmp(who, login->name)) {
		snprintf(why, why_size, "%s's session: a trainee starts only "
			 "their own (you are logged in as %s (trainee))",
			 who, login->name);
		return -EPERM;
	}
	snprintf(out, size, "%s", who);
	return 0;
}

/* While RECORDING records: -EBUSY unless it is WHO's session. */
static int recording_other(const char *recording, const char *who,
			   const char *what, char *why, size_t why_size)
{
	if (!recording || (who && !strcmp(recording, who))) {
		return 0;
	}
	snprintf(why, why_size, "a session%s%s is recording: %s after "
		 "'session stop'", *recording ? " of " : "", recording, what);
	return -EBUSY;
}

int training_login(struct training *t, const struct accounts_user *u,
		   const char *recording, char *why, size_t why_size)
{
	if (u->role != ACCOUNTS_TRAINEE) {
		snprintf(why, why_size, "%s is an %s: only a trainee trains "
			 "at the rig (start a session naming the trainee)",
			 u->name, accounts_role_name(u->role));
		return -EPERM;
	}
	if (recording_other(recording, u->name, "another trainee logs in",
			    why, why_size)) {
		return -EBUSY;
	}
	snprintf(t->trainee, sizeof(t->trainee), "%s", u->name);
	return 0;
}

int training_logout(struct training *t, const struct accounts_user *by,
		    const char *recording, char *why, size_t why_size)
{
	if (by && by->role == ACCOUNTS_TRAINEE && *t->trainee &&
	    strcmp(by->name, t->trainee)) {
		snprintf(why, why_size, "%s is training at the rig: a trainee "
			 "logs out only themself (you are logged in as %s "
			 "(trainee))", t->trainee, by->name);
		return -EPERM;
	}
	if (*t->trainee &&
	    recording_other(recording, NULL, "the trainee logs out", why,
			    why_size)) {
		return -EBUSY;
	}
	t->trainee[0] = '\0';
	return 0;
}

void training_forget(struct training *t, const char *name)
{
	if (!strcmp(t->trainee, name)) {
		t->trainee[0] = '\0';
	}
}
