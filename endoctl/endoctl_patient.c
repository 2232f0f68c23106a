/*
 * endoctl_patient.c - `endoctl patient ...`: the patient's body (its
 * position, the assistant's hand, the handle's valves) over the sockets
 * (endoctl.h).
 */
#include "endoctl/endoctl.h"

#define VALVE_HOLD_S 2.0     /* `valve NAME on` holds it this long ... */
#define VALVE_HOLD_MAX_S 10.0 /* ... or as long as --for says, at most */
#define VALVE_OFF_MS 1       /* `off`: the live input lapses at once */

static const char usage_text[] =
	"endoctl: patient status | position left-lateral|supine|"
	"right-lateral|prone | press SITE [--force N] | release | valve "
	"air|water|suction on [--for S] | valve air|water|suction off | "
	"sedation none|minimal|moderate|deep\n";

/* The newest status; 0 with *REP its reply, or the exit status. */
static int get_status(struct ctl *ctl, Endosim__Reply **rep)
{
	Endosim__GetStatus body = ENDOSIM__GET_STATUS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;

	req.body_case = ENDOSIM__REQUEST__BODY_GET_STATUS;
	req.get_status = &body;
	return ctl_transact(ctl, false, &req, rep);
}

/* Each segment's lumen, fluid and transmural pressure, for people. */
static void print_segments(const Endosim__PatientStatus *p)
{
	printf("%-16s %7s %9s %16s\n", "segment", "factor", "fluid mL",
	       "transmural mmHg");
	for (size_t i = 0; i < p->n_factor && i < p->n_fluid_m3 &&
			   i < p->n_transmural_pa; i++) {
		printf("%-16s %7.3f %9.1f %16.1f\n",
		       anatomy_segment_name((int)i), p->factor[i],
		       p->fluid_m3[i] * 1e6,
		       p->transmural_pa[i] / GAS_PA_PER_MMHG);
	}
}

static void print_patient(const Endosim__PatientStatus *p)
{
	if (!p->enabled) {
		printf("patient   none ([patient] enabled = no); valves %s\n",
		       names_valves(p->valves));
		return;
	}
	printf("position  %s", names_position(p->position));
	if (p->turning) {
		printf(" (turning: %.0f %%)", p->turn * 100);
	}
	printf("\ngas       %.3f L at %.1f mmHg, %.3f L pumped in\n",
	       p->gas_m3 * 1e3, p->pressure_pa / GAS_PA_PER_MMHG,
	       p->gas_in_m3 * 1e3);
	if (*p->site) {
		printf("hand      %s, %.0f N (the pad holds %.1f N)\n", p->site,
		       p->hand_n, p->pad_n);
	} else {
		printf("hand      off\n");
	}
	printf("valves    %s\n", names_valves(p->valves));
	printf("lens      smear %.2f, murk %.2f, red-out %.2f; the tip %s "
	       "fluid\n", p->lens_smear, p->lens_murk, p->lens_redout,
	       p->tip_in_fluid ? "under" : "not in");
	printf("burst     %s\n", p->burst_segment >= 0 ?
	       anatomy_segment_name(p->burst_segment) : "none");
	printf("torn      %s\n", p->torn_segment >= 0 ?
	       anatomy_segment_name(p->torn_segment) : "none");
	printf("sedation  %s\n", names_sedation(p->sedation));
	printf("pain      %.1f of 10 (following %.1f)", p->pain,
	       p->pain_stimulus);
	if (p->pain_cause) {
		printf(": %s", names_pain_cause(p->pain_cause));
		if (p->pain_place >= 0) {
			printf(" in the %s", anatomy_segment_name(p->pain_place));
		}
	}
	printf("\nvitals    heart %.0f /min, SpO2 %.1f %%\n",
	       p->heart_rate_bpm, p->spo2 * 100);
	print_segments(p);
}

static int patient_status(struct ctl *ctl)
{
	Endosim__Reply *rep;
	int r = get_status(ctl, &rep);

	if (r) {
		return r;
	}
	if (!rep->status_reply->patient) {
		fprintf(stderr, "endoctl: endosimd says nothing of a patient "
			"(an older daemon)\n");
		r = EXIT_REFUSED;
	} else if (ctl->json) {
		ctl_json_patient(rep->status_reply->patient);
	} else {
		print_patient(rep->status_reply->patient);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return r;
}

/* A Patient request; on its OK the patient after it, in one line. */
static int patient_request(struct ctl *ctl, Endosim__Patient *body)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	const Endosim__PatientStatus *p;
	Endosim__Reply *rep;
	char line[256];
	int r;

	req.body_case = ENDOSIM__REQUEST__BODY_PATIENT;
	req.patient = body;
	r = ctl_transact(ctl, true, &req, &rep);
	if (r) {
		return r;
	}
	p = rep->body_case == ENDOSIM__REPLY__BODY_STATUS_REPLY ?
		    rep->status_reply->patient : NULL;
	if (ctl->json && p) {
		ctl_json_patient(p);
	} else if (p) {
		ctl_patient_summary(p, line, sizeof(line));
		printf("patient   %s\n", line);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

/* press SITE [--force N] */
static int patient_press(struct ctl *ctl, int argc, char **argv,
			 Endosim__Patient *body)
{
	char *end = NULL;

	if (argc == 5 && !strcmp(argv[3], "--force")) {
		body->force_n = strtod(argv[4], &end);
	}
	if ((argc != 3 && argc != 5) || (end && (*end || end == argv[4]))) {
		fputs(usage_text, stderr);
		return EXIT_USAGE;
	}
	body->action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_PRESS;
	body->site = argv[2];
	return patient_request(ctl, body);
}

/*
 * valve NAME on [--for S] | off: the valves held now (the status'), with
 * NAME pressed or let go, all held for S s (on; off: the default) or
 * lapsing at once (none left pressed), as fingers on the handle would;
 * a hand input of the valves alone: the hand's forces (a scenario's) go
 * on as they were.
 */
static int patient_valve(struct ctl *ctl, int argc, char **argv)
{
	Endosim__HandInput body = ENDOSIM__HAND_INPUT__INIT;
	double hold_s = VALVE_HOLD_S;
	uint32_t bit = argc >= 4 ? names_valve_find(argv[2]) : 0;
	bool on = argc >= 4 && !strcmp(argv[3], "on");
	Endosim__Reply *rep;
	char *end = NULL;
	int r;

	if (on && argc == 6 && !strcmp(argv[4], "--for")) {
		hold_s = strtod(argv[5], &end);
	}
	if (!bit || (argc != 4 && !(on && argc == 6)) ||
	    (!on && strcmp(argv[3], "off")) ||
	    (end && (*end || end == argv[5])) ||
	    !(hold_s > 0 && hold_s <= VALVE_HOLD_MAX_S)) {
		fputs(usage_text, stderr);
		return EXIT_USAGE;
	}
	r = get_status(ctl, &rep);
	if (r) {
		return r;
	}
	body.valves = rep->status_reply->patient ?
			      rep->status_reply->patient->valves : 0;
	endosim__reply__free_unpacked(rep, NULL);
	body.valves = on ? body.valves | bit : body.valves & ~bit;
	body.hold_ms = body.valves ? (uint32_t)lround(hold_s * 1e3)
				   : VALVE_OFF_MS;
	r = ctl_hand_input(ctl, &body);
	if (r) {
		return r;
	}
	if (ctl->json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_uint(&j, "status", 0);
		json_string(&j, "valves", names_valves(body.valves));
		json_double(&j, "hold_s", body.hold_ms / 1e3);
		json_object_end(&j);
	} else if (body.valves) {
		printf("valves %s for %.1f s\n", names_valves(body.valves),
		       body.hold_ms / 1e3);
	} else {
		printf("valves none\n");
	}
	return 0;
}

int ctl_cmd_patient(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Patient body = ENDOSIM__PATIENT__INIT;
	const char *sub = argc >= 2 ? argv[1] : "";

	if (argc == 2 && !strcmp(sub, "status")) {
		return patient_status(ctl);
	}
	if (argc == 3 && !strcmp(sub, "position")) {
		body.action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_TURN;
		body.position = argv[2];
		return patient_request(ctl, &body);
	}
	if (argc >= 3 && !strcmp(sub, "press")) {
		return patient_press(ctl, argc, argv, &body);
	}
	if (argc == 2 && !strcmp(sub, "release")) {
		body.action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_RELEASE;
		return patient_request(ctl, &body);
	}
	if (argc >= 4 && !strcmp(sub, "valve")) {
		return patient_valve(ctl, argc, argv);
	}
	if (argc == 3 && !strcmp(sub, "sedation")) {
		body.action = ENDOSIM__PATIENT_ACTION__PATIENT_ACTION_SEDATE;
		body.sedation = argv[2];
		return patient_request(ctl, &body);
	}
	fputs(usage_text, stderr);
	return EXIT_USAGE;
}
