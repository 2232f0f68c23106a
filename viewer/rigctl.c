/* rigctl.c - see rigctl.h. */
#include "viewer/rigctl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "session/accounts.h"
#include "viewer/reconnect.h"

struct rigctl {
	struct reconnect *rc; /* the read-write socket */
	struct reconnect *ro; /* the read-only one: who trains */
	uint64_t asked_ns;    /* who trains, asked last; 0: at once */
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
	r->ro = reconnect_create(socket, false, RIGCTL_RETRY_S, LOG_DEBUG,
				 "who trains: ");
	if (!r->rc || !r->ro) {
		rigctl_destroy(r);
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
	reconnect_destroy(r->ro);
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

/* Sends REQ, waiting TIMEOUT_MS for its reply; a failed exchange drops
 * the connection. *REP on success. */
static int exchange_within(struct rigctl *r, Endosim__Request *req,
			   Endosim__Reply **rep, uint64_t now_ns,
			   int timeout_ms)
{
	int err = connect_rw(r, now_ns);

	if (err) {
		return err;
	}
	err = reconnect_request(r->rc, req, rep, timeout_ms);
	if (err) {
		r->driving = false;
		reconnect_say(r->rc, "control socket: %s", strerror(-err));
	}
	return err;
}

static int exchange(struct rigctl *r, Endosim__Request *req,
		    Endosim__Reply **rep, uint64_t now_ns)
{
	return exchange_within(r, req, rep, now_ns, RIGCTL_TIMEOUT_MS);
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

/* ------------------------------------------------------------ who trains */

int rigctl_trainee(struct rigctl *r, uint64_t now_ns, bool *asks,
		   char *trainee, size_t size)
{
	Endosim__GetStatus body = ENDOSIM__GET_STATUS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int err;

	if (r->asked_ns &&
	    now_ns - r->asked_ns < (uint64_t)(RIGCTL_TRAINEE_POLL_S * 1e9)) {
		return 0;
	}
	r->asked_ns = now_ns;
	err = reconnect_connect(r->ro, now_ns);
	if (err < 0) {
		return err;
	}
	req.body_case = ENDOSIM__REQUEST__BODY_GET_STATUS;
	req.get_status = &body;
	err = reconnect_request(r->ro, &req, &rep, RIGCTL_TIMEOUT_MS);
	if (err) {
		reconnect_say(r->ro, "%s", strerror(-err));
		return err;
	}
	err = rep->status == ENDOSIM__STATUS__STATUS_OK &&
	      rep->body_case == ENDOSIM__REPLY__BODY_STATUS_REPLY ? 1 : -EPROTO;
	if (err == 1) {
		*asks = rep->status_reply->asks_trainee;
		snprintf(trainee, size, "%s", rep->status_reply->trainee);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return err;
}

void rigctl_trainee_now(struct rigctl *r)
{
	r->asked_ns = 0;
}

/* REQ (a Login or Logout) sent, WHAT said of it into r->said and, with
 * who trains after it, into TRAINEE; the refusal's or the failure's
 * words into WORDS. */
static int account(struct rigctl *r, Endosim__Request *req, const char *what,
		   uint64_t now_ns, char *trainee, size_t trainee_size,
		   char *words, size_t size)
{
	Endosim__Reply *rep;
	int err;

	reconnect_now(r->rc); /* the trainee asked: try now */
	err = exchange_within(r, req, &rep, now_ns, RIGCTL_LOGIN_TIMEOUT_MS);
	if (err) {
		snprintf(words, size, "%s", reconnect_problem(r->rc));
		snprintf(r->said, sizeof(r->said), "%s: %s", what, words);
		return err;
	}
	if (rep->status == ENDOSIM__STATUS__STATUS_OK &&
	    rep->body_case == ENDOSIM__REPLY__BODY_ACCOUNTS) {
		snprintf(trainee, trainee_size, "%s", rep->accounts->training);
		snprintf(r->said, sizeof(r->said), "%s: %s%s", what,
			 *trainee ? trainee : "nobody",
			 " trains at the rig");
	} else {
		snprintf(words, size, "%s", reason(rep));
		snprintf(r->said, sizeof(r->said), "%s refused: %s", what,
			 words);
		err = -EACCES;
	}
	r->asked_ns = 0; /* and who trains asked again */
	endosim__reply__free_unpacked(rep, NULL);
	return err;
}

int rigctl_login(struct rigctl *r, const char *name, const char *pin,
		 uint64_t now_ns, char *trainee, char *words, size_t size)
{
	Endosim__Login body = ENDOSIM__LOGIN__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;

	body.name = (char *)name;
	body.pin = (char *)pin;
	body.training = true;
	req.body_case = ENDOSIM__REQUEST__BODY_LOGIN;
	req.login = &body;
	return account(r, &req, "login", now_ns, trainee, size, words, size);
}

int rigctl_logout(struct rigctl *r, uint64_t now_ns, char *words,
		  size_t size)
{
	Endosim__Logout body = ENDOSIM__LOGOUT__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	char trainee[ACCOUNTS_NAME_MAX + 1];

	req.body_case = ENDOSIM__REQUEST__BODY_LOGOUT;
	req.logout = &body;
	return account(r, &req, "log out", now_ns, trainee, sizeof(trainee),
		       words, size);
}
