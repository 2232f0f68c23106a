/*
 * training.h - who trains at the rig now (docs/TRAINEE.md "Who is
 * training"): the rig's one current trainee, set by a trainee's login at
 * endoview (proto's Login with training; endoctl login) and cleared by a
 * logout (endoview's C key; endoctl logout), by that user's removal, or
 * when endosimd exits (it is kept in memory only: a restarted daemon asks
 * again). A session's end does not clear it: a trainee records several in
 * a row. The rules, as functions of what the control thread holds
 * (control_training.c applies them to the requests):
 *
 *  - a session's trainee: the one SessionStart names, else the rig's
 *    trainee, else the starting connection's login when it is a
 *    trainee's, else nobody ("", as on a rig without accounts). Refused
 *    when the rig's trainee is another than the one named (they log out
 *    first), and when a trainee's login would start another's session;
 *  - a training login: a trainee's only (an instructor or administrator
 *    teaches, and starts sessions naming the trainee); refused while a
 *    session of another records, so that who trains is the recording
 *    session's trainee;
 *  - a logout: refused while a session records, and to a trainee logged
 *    in as another.
 *
 * Each refusal puts its words into WHY (SIZE bytes) and changes nothing.
 * No allocation, no locking: the control thread, or a test.
 */
#ifndef ENDOSIM_TRAINING_H
#define ENDOSIM_TRAINING_H

#include <stdbool.h>
#include <stddef.h>

#include "session/accounts.h"

struct training {
	char trainee[ACCOUNTS_NAME_MAX + 1]; /* who trains; "": nobody */
	bool asks;  /* the accounts hold a trainee: endoview asks who trains */
};

/*
 * The trainee of a session started now into OUT (SIZE bytes): NAMED (""
 * none), else T's, else LOGIN's when it is a trainee (LOGIN NULL: not
 * logged in), else "". 0; -EBUSY (the rig's trainee is another than
 * NAMED); -EPERM (LOGIN a trainee, the session another's).
 */
int training_session(const struct training *t, const char *named,
		     const struct accounts_user *login, char *out,
		     size_t size, char *why, size_t why_size);

/*
 * U (logged in with their PIN) trains at the rig from now on, while the
 * session of RECORDING records (NULL: none records; "": a session of
 * nobody). 0; -EPERM (U is no trainee); -EBUSY (a session of another
 * records).
 */
int training_login(struct training *t, const struct accounts_user *u,
		   const char *recording, char *why, size_t why_size);

/*
 * Nobody trains at the rig any more, as BY asks (NULL: not logged in: the
 * staff), while RECORDING records (as training_login()). 0 (also when
 * nobody trained); -EPERM (BY a trainee, another trains); -EBUSY (a
 * session records).
 */
int training_logout(struct training *t, const struct accounts_user *by,
		    const char *recording, char *why, size_t why_size);

/* The user NAME is gone: nobody trains if they did. */
void training_forget(struct training *t, const char *name);

#endif
