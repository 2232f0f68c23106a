/*
 * control_patient.c - the patient's commands (the Patient request): the
 * names checked here, on the control thread, against the positions and
 * the loaded case's sites, so that a refusal lists the valid ones and
 * nothing reaches the loop; the loop applies the rest through its
 * patient mailbox (loop_patient_command()) and answers within a cycle or
 * two. The reply is the status of the cycle that took the command.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/log.h"
#include "control/control_private.h"
#include "proto/names.h"

/* "llq, umbilical": the case's sites, into OUT (SIZE bytes). */
static void site_names(const struct anatomy *a, char *out, size_t size)
{
	size_t n = 0;

	out[0] = '\0';
	for (int i = 0; a && i < a->sites && n < size; i++) {
		n += (size_t)snprintf(out + n, size - n, "%s%s", i ? ", " : "",
				      a->site[i].name);
	}
}

/* The turn asked for, or false with REP refused (the positions listed). */
static bool turn_of(struct control *c, const Endosim__Patient *p,
		    struct loop_patient_command *cmd, Endosim__Reply *rep)
{
	int position = names_position_find(p->position);

	if (position < 0) {
		snprintf(c->refusal, sizeof(c->refusal), "patient: no "
			 "position '%.63s': left-lateral, supine, "
			 "right-lateral or prone", p->position);
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
		return false;
	}
	*cmd = (struct loop_patient_command){ LOOP_PATIENT_TURN, position, 0 };
	return true;
}

/* The press asked for, or false with REP refused (the sites listed, the
 * strongest press said). */
static bool press_of(struct control *c, const Endosim__Patient *p,
		     struct loop_patient_command *cmd, Endosim__Reply *rep)
{
	const struct anatomy *a = colon_anatomy(c->colon);
	int site = a ? anatomy_site_find(a, p->site) : -1;
	double max = c->cfg.patient.hand_max_n;
	char names[ANATOMY_MAX_SITES * (ANATOMY_NAME + 2)];

	if (site < 0) {
		site_names(a, names, sizeof(names));
		snprintf(c->refusal, sizeof(c->refusal), "patient: no site "
			 "'%.63s' in case %.63s: %.350s", p->site,
			 colon_name(c->colon), *names ? names : "it has none");
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
		return false;
	}
	if (!(p->force_n >= 0 && p->force_n <= max)) {
		snprintf(c->refusal, sizeof(c->refusal), "patient: a press of "
			 "%g N: from 0 (the default, %g N) to %g N ([patient] "
			 "hand_max_n)", p->force_n, c->cfg.patient.hand_n,
			 max);
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
		return false;
	}
	*cmd = (struct loop_patient_command){ LOOP_PATIENT_PRESS, site,
					      p->force_n };
	return true;
}

/* The sedation NAME, or -1 with REP refused (the levels listed). */
static int sedation_of(struct control *c, const char *name,
		       Endosim__Reply *rep)
{
	int s = names_sedation_find(name);

	if (s < 0) {
		snprintf(c->refusal, sizeof(c->refusal), "patient: no "
			 "sedation '%.63s': none, minimal, moderate or deep",
			 name);
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
	}
	return s;
}

/* Whether the published state has the patient enabled. */
static bool patient_on(struct control *c)
{
	struct endosim_state st;

	return !publish_read(c->deps.pub, &st) && st.patient.enabled;
}

/* CMD to the loop: 0, or -1 with REP refused. */
static int to_loop(struct control *c, const struct loop_patient_command *cmd,
		   Endosim__Reply *rep)
{
	int r = loop_patient_command(c->deps.loop, cmd, COMMAND_TIMEOUT_MS);

	if (r == -EINVAL) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "patient: refused by the force loop");
	} else if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
	}
	return r ? -1 : 0;
}

int control_sedate(struct control *c, struct client *cl, const char *name,
		   Endosim__Reply *rep)
{
	struct loop_patient_command cmd = { LOOP_PATIENT_SEDATE,
					    c->cfg.pain.sedation, 0 };

	if (!patient_on(c)) {
		if (!*name) {
			return 0;
		}
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "sedation: there is no patient ([patient] enabled = "
		       "no)");
		return -1;
	}
	if (*name && (cmd.arg = sedation_of(c, name, rep)) < 0) {
		return -1;
	}
	if (to_loop(c, &cmd, rep)) {
		return -1;
	}
	log_notice("patient: sedation %s by uid %d", names_sedation(
			   (uint32_t)cmd.arg), (int)cl->uid);
	return 0;
}

/* CMD to the loop; on its 0 the reply is the status after it. */
static void hand_over(struct control *c, struct client *cl,
		      const struct loop_patient_command *cmd,
		      const Endosim__Patient *p, Endosim__Reply *rep)
{
	if (to_loop(c, cmd, rep)) {
		return;
	}
	if (cmd->op == LOOP_PATIENT_TURN) {
		log_notice("patient: turned to %s by uid %d", p->position,
			   (int)cl->uid);
	} else if (cmd->op == LOOP_PATIENT_PRESS) {
		log_notice("patient: pressed at %s with %g N by uid %d",
			   p->site, p->force_n > 0 ? p->force_n :
			   c->cfg.patient.hand_n, (int)cl->uid);
	} else {
		log_notice("patient: released by uid %d", (int)cl->uid);
	}
	control_await_state(c);
	control_build_status(c, rep);
}

void control_on_patient(struct control *c, struct client *cl,
			const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__Patient *p = req->patient;
	struct loop_patient_command cmd = { LOOP_PATIENT_RELEASE, 0, 0 };

	if (!patient_on(c)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "patient: there is none ([patient] enabled = no)");
		return;
	}
	switch (p->action) {
	case ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_TURN:
		if (!turn_of(c, p, &cmd, rep)) {
			return;
		}
		break;
	case ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_PRESS:
		if (!press_of(c, p, &cmd, rep)) {
			return;
		}
		break;
	case ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_RELEASE:
		break;
	case ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_SEDATE:
		if (control_sedate(c, cl, p->sedation, rep) == 0) {
			control_await_state(c);
			control_build_status(c, rep);
		}
		return;
	default:
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "patient: no such action");
		return;
	}
	hand_over(c, cl, &cmd, p, rep);
}
