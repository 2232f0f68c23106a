/*
 * endoctl.h - what the parts of endoctl share (endoctl.c: talking to
 * endosimd, the daemon's commands, main; endoctl_print.c: printing its
 * replies; endoctl_session.c: training sessions; endoctl_map.c: the
 * recording session's unseen-mucosa map; endoctl_trainee.c: a trainee's
 * course; endoctl_records.c: the rig's records; endoctl_guide.c: guided
 * replay; endoctl_patient.c: the patient; endoctl_tool.c: the tool in the
 * working channel). One thread.
 */
#ifndef ENDOSIM_ENDOCTL_H
#define ENDOSIM_ENDOCTL_H

#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "proto/client.h"
#include "proto/endosim_shm.h"
#include "proto/fields.h"
#include "proto/names.h"
#include "proto/version.h"
#include "base/json.h"
#include "model/anatomy.h"
#include "model/gas.h"
#include "model/objio.h"
#include "session/report.h"
#include "session/sessiondir.h"
#include "session/sessionpb.h"
#include "session/sessionview.h"

enum {
	EXIT_REFUSED = 1,
	EXIT_USAGE = 2,
	EXIT_NO_DAEMON = 3,
	EXIT_COMM = 4,
};

struct ctl {
	const char *socket; /* --socket, or NULL */
	bool json;
	int timeout_ms;
	struct client *client;
	const char *as;     /* --as NAME: each connection logs in; NULL not */
	char pin[128];      /* its PIN, once read ("": not yet) */
};

typedef int command_fn(struct ctl *ctl, int argc, char **argv);

/*
 * Sends REQ over the read-only or (WRITE) the read-write socket; 0 with an
 * OK reply in *REP (endosim__reply__free_unpacked() it), or the exit
 * status with the reason on stderr (and, with --json, on stdout).
 */
int ctl_transact(struct ctl *ctl, bool write, Endosim__Request *req,
		 Endosim__Reply **rep);

/* REQ on the connection ctl_transact() made last, as it: 0 or the exit
 * status. */
int ctl_request(struct ctl *ctl, Endosim__Request *req,
		Endosim__Reply **rep);

/* BODY, a hand input (simulated rig), on the read-write socket: 0 or the
 * exit status (ctl_transact()'s). */
int ctl_hand_input(struct ctl *ctl, Endosim__HandInput *body);

/* A status or stats reply, as text or one JSON object (endoctl_print.c). */
void ctl_print_status(const Endosim__StatusReply *s);
void ctl_json_status(const Endosim__StatusReply *s);
void ctl_print_stats(const Endosim__StatsReply *s, bool json);

/*
 * The patient in one line, for `status` and `patient status`: where it
 * lies (turning), the gas (L, mmHg), the hand, the valves, a
 * perforation. Into OUT (SIZE bytes, NUL-terminated).
 */
void ctl_patient_summary(const Endosim__PatientStatus *p, char *out,
			 size_t size);

/* `endoctl session ...` (endoctl_session.c). */
int ctl_cmd_session(struct ctl *ctl, int argc, char **argv);

/* `endoctl session map`: the recording session's unseen-mucosa map
 * (endoctl_map.c); 0 or the exit status. */
int ctl_session_map(struct ctl *ctl);

/* `endoctl trainee ...` (endoctl_trainee.c). */
int ctl_cmd_trainee(struct ctl *ctl, int argc, char **argv);

/* `endoctl records check | rebuild` (endoctl_records.c). */
int ctl_cmd_records(struct ctl *ctl, int argc, char **argv);

/*
 * The connection just made logged in as --as NAME (endoctl_accounts.c):
 * its PIN from $ENDOSIM_PIN, else asked on the terminal (once). 0, or the
 * exit status with the reason on stderr (ctl_transact()'s).
 */
int ctl_login(struct ctl *ctl);

/* A PIN for PROMPT into PIN (SIZE): $VAR, else the terminal, unechoed
 * (ASK_TWICE: a new PIN, typed again to confirm). 0 or EXIT_USAGE. */
int ctl_read_pin(const char *var, const char *prompt, bool ask_twice,
		 char *pin, size_t size);

/* `endoctl user ...`, `endoctl group ...`, `endoctl whoami`
 * (endoctl_accounts.c). */
int ctl_cmd_user(struct ctl *ctl, int argc, char **argv);
int ctl_cmd_group(struct ctl *ctl, int argc, char **argv);
int ctl_cmd_whoami(struct ctl *ctl, int argc, char **argv);

/* `endoctl login NAME`, `endoctl logout`: who trains at the rig
 * (endoctl_training.c). */
int ctl_cmd_login(struct ctl *ctl, int argc, char **argv);
int ctl_cmd_logout(struct ctl *ctl, int argc, char **argv);

/* `endoctl guide ...` (endoctl_guide.c). */
int ctl_cmd_guide(struct ctl *ctl, int argc, char **argv);

/* `endoctl patient ...` (endoctl_patient.c). */
int ctl_cmd_patient(struct ctl *ctl, int argc, char **argv);

/* The patient as one JSON object, its fields in fields.h's order. */
void ctl_json_patient(const Endosim__PatientStatus *p);

/* MSG, a message of table T's (fields.h), as one JSON object. */
void ctl_json_part(const struct fields_table *t, const void *msg);

/* `endoctl tool ...` (endoctl_tool.c). */
int ctl_cmd_tool(struct ctl *ctl, int argc, char **argv);

#endif
