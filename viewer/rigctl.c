/* rigctl.c - see rigctl.h. */
#include "viewer/rigctl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "viewer/reconnect.h"

struct rigctl {
	struct reconnect *rc; /* the read-write socket */
	bool hand_refused;    /* until the next connection */
	bool driving;
	char said[256];
};

struct rigctl *rigctl_create(const char *socket)
{
	struct rigctl *r = calloc(1, sizeof(*r));

	if (!r) {
		return NULL;
	}
	r->rc = reconnect_create(socket, true, RIGCTL_RETRY_S, LOG_NOTICE, "");
	if (!r->rc) {
		free(r);
		return NULL;
	}
	return r;
}

void rigctl_destroy(struct rigctl *r)
{
	if (!r) {
		return;
	}
	reconnect_destroy(r->rc);
	free(r);
}

static int connect_rw(struct rigctl *r, uint64_t now_ns)
{
	int err = reconnect_connect(r->rc, now_ns);

	if (err == 1) {
		reconnect_clear(r->rc);
		r->hand_refused = false;
		return 0;
	}
	if (err && err != -EAGAIN) {
		reconnect_say(r->rc, "%s: %s: viewing only",
			      reconnect_path(r->rc), err == -EACCES ?
			      "no permission (not in the endosim group)" :
			      strerror(-err));
	}
	return err;
}

/* Sends REQ; a failed exchange drops the connection. *REP on success. */
static int exchange(struct rigctl *r, Endosim__Request *req,
		    Endosim__Reply **rep, uint64_t now_ns)
{
	int err = connect_rw(r, now_ns);

	if (err) {
		return err;
	}
	err = reconnect_request(r->rc, req, rep, RIGCTL_TIMEOUT_MS);
	if (err) {
		r->driving = false;
		reconnect_say(r->rc, "control socket: %s", strerror(-err));
	}
	return err;
}

static const char *reason(const Endosim__Reply *rep)
{
	return rep->error && *rep->error ? rep->error :
					   client_status_text(rep->status);
}

/* BODY to endosimd: 0, or a negative errno (-EACCES: refused). */
static int send_hand(struct rigctl *r, Endosim__HandInput *body,
		     uint64_t now_ns)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int err;

	if (r->hand_refused) {
		return -EACCES;
	}
	req.body_case = ENDOSIM__REQUEST__BODY_HAND_INPUT;
	req.hand_input = body;
	err = exchange(r, &req, &rep, now_ns);
	if (err) {
		return err;
	}
	r->driving = rep->status == ENDOSIM__STATUS__STATUS_OK;
	if (!r->driving && rep->status != ENDOSIM__STATUS__STATUS_BAD_VALUE) {
		reconnect_say(r->rc, "hand input refused: %s", reason(rep));
		r->hand_refused = true;
	}
	endosim__reply__free_unpacked(rep, NULL);
	return r->driving ? 0 : -EACCES;
}

int rigctl_hand(struct rigctl *r, const double force[ENDOSIM_AXES],
		uint32_t valves, uint32_t hold_ms, uint64_t now_ns)
{
	Endosim__HandInput body = ENDOSIM__HAND_INPUT__INIT;

	body.n_force = force ? ENDOSIM_AXES : 0;
	body.force = (double *)force;
	body.hold_ms = hold_ms;
	body.valves = valves;
	return send_hand(r, &body, now_ns);
}

int rigctl_hands_off(struct rigctl *r, uint64_t now_ns)
{
	Endosim__HandInput body = ENDOSIM__HAND_INPUT__INIT;

	body.hands_off = true;
	return send_hand(r, &body, now_ns);
}

static const char *const command_name[] = {
	[RIGCTL_ENABLE] = "enable", [RIGCTL_DISABLE] = "disable",
	[RIGCTL_ESTOP] = "estop", [RIGCTL_RESET] = "reset",
	[RIGCTL_GUIDE_TAKEOVER] = "take over",
	[RIGCTL_GUIDE_RESUME] = "resume the guidance",
	[RIGCTL_GUIDE_RESET] = "back to the path",
};

static void command_body(Endosim__Request *req, enum rigctl_command cmd)
{
	static Endosim__Enable enable = ENDOSIM__ENABLE__INIT;
	static Endosim__Disable disable = ENDOSIM__DISABLE__INIT;
	static Endosim__EStop estop = ENDOSIM__ESTOP__INIT;
	static Endosim__ResetFault reset = ENDOSIM__RESET_FAULT__INIT;
	static Endosim__Guide guide = ENDOSIM__GUIDE__INIT;

	switch (cmd) {
	case RIGCTL_ENABLE:
		req->body_case = ENDOSIM__REQUEST__BODY_ENABLE;
		req->enable = &enable;
		break;
	case RIGCTL_DISABLE:
		req->body_case = ENDOSIM__REQUEST__BODY_DISABLE;
		req->disable = &disable;
		break;
	case RIGCTL_ESTOP:
		req->body_case = ENDOSIM__REQUEST__BODY_ESTOP;
		req->estop = &estop;
		break;
	case RIGCTL_RESET:
		req->body_case = ENDOSIM__REQUEST__BODY_RESET_FAULT;
		req->reset_fault = &reset;
		break;
	case RIGCTL_GUIDE_TAKEOVER:
	case RIGCTL_GUIDE_RESUME:
	case RIGCTL_GUIDE_RESET:
		guide.action = cmd == RIGCTL_GUIDE_TAKEOVER ?
			       ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_TAKEOVER :
			       cmd == RIGCTL_GUIDE_RESUME ?
			       ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESUME :
			       ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESET;
		req->body_case = ENDOSIM__REQUEST__BODY_GUIDE;
		req->guide = &guide;
		break;
	case RIGCTL_COMMANDS:
		break;
	}
}

/* Sends REQ for what WHAT names; the outcome in r->said. */
static int command(struct rigctl *r, Endosim__Request *req, const char *what,
		   uint64_t now_ns)
{
	Endosim__Reply *rep;
	int err;

	reconnect_now(r->rc); /* the trainee asked: try now */
	err = exchange(r, req, &rep, now_ns);
	if (err) {
		snprintf(r->said, sizeof(r->said), "%s: %s", what,
			 reconnect_problem(r->rc));
		return err;
	}
	if (rep->status == ENDOSIM__STATUS__STATUS_OK) {
		snprintf(r->said, sizeof(r->said), "%s: done", what);
	} else {
		snprintf(r->said, sizeof(r->said), "%s refused: %s", what,
			 reason(rep));
		err = -EACCES;
	}
	log_info("%s", r->said);
	endosim__reply__free_unpacked(rep, NULL);
	return err;
}

int rigctl_command(struct rigctl *r, enum rigctl_command cmd,
		   uint64_t now_ns)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;

	command_body(&req, cmd);
	return command(r, &req, command_name[cmd], now_ns);
}

int rigctl_patient(struct rigctl *r, enum rigctl_patient what,
		   const char *name, uint64_t now_ns)
{
	Endosim__Patient body = ENDOSIM__PATIENT__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	char words[96];

	switch (what) {
	case RIGCTL_PATIENT_TURN:
		body.action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_TURN;
		body.position = (char *)name;
		snprintf(words, sizeof(words), "turn to %s", name);
		break;
	case RIGCTL_PATIENT_PRESS:
		body.action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_PRESS;
		body.site = (char *)name;
		snprintf(words, sizeof(words), "the hand on %s", name);
		break;
	default:
		body.action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_RELEASE;
		snprintf(words, sizeof(words), "the hand off");
	}
	req.body_case = ENDOSIM__REQUEST__BODY_PATIENT;
	req.patient = &body;
	return command(r, &req, words, now_ns);
}

const char *rigctl_problem(const struct rigctl *r)
{
	return reconnect_problem(r->rc);
}

const char *rigctl_said(const struct rigctl *r)
{
	return r->said;
}

bool rigctl_driving(const struct rigctl *r)
{
	return r->driving;
}
