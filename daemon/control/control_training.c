/*
 * control_training.c - who trains at the rig (training.h) on the
 * requests (control_private.h): a Login with training, Logout, the
 * trainee of a session started; and whether the accounts hold a trainee
 * at all (StatusReply.asks_trainee: endoview asks who is training only
 * then) and the rig's trainee still (removed on this rig or at the
 * centre: nobody trains), looked up at start-up and after each change of
 * the accounts (control_accounts_refresh()), never per status (a push
 * may ask for one every few ms).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "control/control_private.h"

void control_training_users(struct control *c,
			    const struct accounts_user *u, size_t n)
{
	const char *name = c->training.trainee;
	bool any = false, still = !*name;

	if (!u) {
		c->training.asks = false;
		return; /* not known: who trains stays */
	}
	for (size_t i = 0; i < n; i++) {
		if (u[i].role == ACCOUNTS_TRAINEE) {
			any = true;
			still |= !strcmp(u[i].name, name);
		}
	}
	c->training.asks = any;
	if (!still) {
		log_notice("%s no longer trains at the rig: no such trainee "
			   "in the accounts now", name);
		training_forget(&c->training, name);
	}
}


/* The trainee of the recording session, NULL when none records. */
static const char *recording(struct control *c, struct recorder_info *ri)
{
	recorder_info(c->deps.recorder, ri);
	return ri->active && ri->recording ? ri->trainee : NULL;
}

static bool refused(struct control *c, Endosim__Reply *rep, int e)
{
	refuse(rep, e == -EBUSY ? ENDOSIM__STATUS__STATUS_REFUSED
				: ENDOSIM__STATUS__STATUS_PERMISSION,
	       c->refusal);
	return true;
}

bool control_training_refused(struct control *c, const struct client *cl,
			      const Endosim__Login *m,
			      const struct accounts_user *u,
			      Endosim__Reply *rep)
{
	struct recorder_info ri;
	int e;

	if (!m->training) {
		return false;
	}
	if (!cl->may_command) {
		snprintf(c->refusal, sizeof(c->refusal), "who trains at the "
			 "rig is set on the control socket, by root or the "
			 "command group (endoview on the rig)");
		return refused(c, rep, -EPERM);
	}
	if (!u) { /* before the PIN's hash: what its name alone refuses */
		struct accounts_user named = { .role = ACCOUNTS_TRAINEE };
		struct training scratch = c->training;

		snprintf(named.name, sizeof(named.name), "%s", m->name);
		e = training_login(&scratch, &named, recording(c, &ri),
				   c->refusal, sizeof(c->refusal));
		return e && refused(c, rep, e);
	}
	e = training_login(&c->training, u, recording(c, &ri), c->refusal,
			   sizeof(c->refusal));
	if (e) {
		return refused(c, rep, e);
	}
	log_notice("%s trains at the rig (login from uid %d, pid %d)",
		   u->name, (int)cl->uid, (int)cl->pid);
	return false;
}

int control_training_session(struct control *c, const struct client *cl,
			     const char *named, char *out, size_t size,
			     Endosim__Reply *rep)
{
	int e = training_session(&c->training, named,
				 cl->logged_in ? &cl->user : NULL, out, size,
				 c->refusal, sizeof(c->refusal));

	return e && refused(c, rep, e) ? -1 : 0;
}

void control_on_logout(struct control *c, struct client *cl,
		       const Endosim__Request *req, Endosim__Reply *rep)
{
	char was[sizeof(c->training.trainee)];
	struct recorder_info ri;
	int e;

	(void)req;
	snprintf(was, sizeof(was), "%s", c->training.trainee);
	e = training_logout(&c->training, cl->logged_in ? &cl->user : NULL,
			    recording(c, &ri), c->refusal, sizeof(c->refusal));
	if (e) {
		refused(c, rep, e);
		return;
	}
	if (*was) {
		log_notice("%s no longer trains at the rig (logout from uid "
			   "%d, pid %d)", was, (int)cl->uid, (int)cl->pid);
	}
	cl->logged_in = false;
	endosim__accounts_reply__init(&c->logout);
	c->logout.staff = cl->staff;
	c->logout.training = "";
	rep->body_case = ENDOSIM__REPLY__BODY_ACCOUNTS;
	rep->accounts = &c->logout;
}
