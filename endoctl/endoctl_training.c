/*
 * endoctl_training.c - who trains at the rig (endoctl.h): `endoctl login
 * NAME` (proto's Login with training, as endoview's login screen sends
 * it; the PIN from $ENDOSIM_PIN or the terminal) and `endoctl logout`
 * (Logout), both on the read-write socket. The rules are endosimd's
 * (daemon/control/training.h).
 */
#include "endoctl/endoctl.h"

/* Who trains at the rig now, as REP says, in words or JSON. */
static void print_training(const struct ctl *ctl, const Endosim__Reply *rep)
{
	const char *who = rep->body_case == ENDOSIM__REPLY__BODY_ACCOUNTS ?
			  rep->accounts->training : "";
	struct json j;

	if (ctl->json) {
		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_string(&j, "training", who);
		json_object_end(&j);
	} else if (*who) {
		printf("%s trains at the rig\n", who);
	} else {
		printf("nobody trains at the rig\n");
	}
}

/* REQ on the read-write socket, its answer printed. */
static int send_training(struct ctl *ctl, Endosim__Request *req)
{
	Endosim__Reply *rep;
	int r = ctl_transact(ctl, true, req, &rep);

	if (!r) {
		print_training(ctl, rep);
		endosim__reply__free_unpacked(rep, NULL);
	}
	return r;
}

int ctl_cmd_login(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Login body = ENDOSIM__LOGIN__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	char prompt[160], pin[128];
	int r;

	if (argc != 2) {
		fputs("usage: endoctl login NAME\n", stderr);
		return EXIT_USAGE;
	}
	snprintf(prompt, sizeof(prompt), "PIN of %s: ", argv[1]);
	if ((r = ctl_read_pin("ENDOSIM_PIN", prompt, false, pin,
			      sizeof(pin)))) {
		return r;
	}
	body.name = argv[1];
	body.pin = pin;
	body.training = true;
	req.body_case = ENDOSIM__REQUEST__BODY_LOGIN;
	req.login = &body;
	r = send_training(ctl, &req);
	explicit_bzero(pin, sizeof(pin));
	return r;
}

int ctl_cmd_logout(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Logout body = ENDOSIM__LOGOUT__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;

	(void)argv;
	if (argc != 1) {
		fputs("usage: endoctl logout\n", stderr);
		return EXIT_USAGE;
	}
	req.body_case = ENDOSIM__REQUEST__BODY_LOGOUT;
	req.logout = &body;
	return send_training(ctl, &req);
}
