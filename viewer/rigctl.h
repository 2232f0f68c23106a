/*
 * rigctl.h - endoview's commands to endosimd over the read-write socket
 * (control.sock, the endosim group): the simulated hand's forces
 * (HandInput) and the handle's valves with them, the state machine
 * (enable, disable, estop, reset), guided replay's take-over, resume and
 * reset, the patient's (Patient: a turn, the assistant's hand), and who
 * trains at the rig (login.h: a trainee's Login, Logout; asked on the
 * read-only socket, GetStatus, at most every RIGCTL_TRAINEE_POLL_S, on a
 * connection of its own whose problems are only logged at debug level:
 * the link says the same).
 *
 * The connection (reconnect.h) is made when first needed and again, at
 * most every RIGCTL_RETRY_S, after it failed. What cannot be done is said
 * in rigctl_problem() for the screen, and logged once (no permission: the
 * viewer only views; the rig is not simulated: the real handle drives
 * it), and hand input is not sent again until the connection is made
 * anew.
 *
 * Each request waits for its reply at most RIGCTL_TIMEOUT_MS (the
 * daemon's control thread answers within a millisecond or two). Main
 * thread only.
 */
#ifndef ENDOVIEW_RIGCTL_H
#define ENDOVIEW_RIGCTL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "proto/endosim_shm.h"

#define RIGCTL_RETRY_S 1.0
#define RIGCTL_TIMEOUT_MS 200
#define RIGCTL_LOGIN_TIMEOUT_MS 3000 /* a PIN's hash takes endosimd ~40 ms,
					more on a loaded machine: the frame
					waits for it, once, as the trainee
					asked */
#define RIGCTL_TRAINEE_POLL_S 1.0

enum rigctl_command {
	RIGCTL_ENABLE,
	RIGCTL_DISABLE,
	RIGCTL_ESTOP,
	RIGCTL_RESET,
	/* guided replay (endoctl guide): take over, resume at the nearest
	   point, back to the path's nearest point and held */
	RIGCTL_GUIDE_TAKEOVER,
	RIGCTL_GUIDE_RESUME,
	RIGCTL_GUIDE_RESET,
	RIGCTL_COMMANDS
};

struct rigctl;

/* SOCKET: as client_socket_path() takes it (NULL: the default). */
struct rigctl *rigctl_create(const char *socket);

/* NULL is fine. */
void rigctl_destroy(struct rigctl *r);

/*
 * The hand's FORCE per axis (N, N m) and the VALVES it holds (enum
 * endosim_valve bits), holding HOLD_MS; FORCE NULL: the valves alone,
 * leaving the forces (a scenario's) as they are. Returns 0, or a negative
 * errno (-EACCES: refused, see rigctl_problem()).
 */
int rigctl_hand(struct rigctl *r, const double force[ENDOSIM_AXES],
		uint32_t valves, uint32_t hold_ms, uint64_t now_ns);

/* Hands off: endosimd's hand lets go of every axis it holds where the
 * input left it (hand.h). 0, or as rigctl_hand(). */
int rigctl_hands_off(struct rigctl *r, uint64_t now_ns);

enum rigctl_patient {
	RIGCTL_PATIENT_TURN,    /* to the position NAME ("supine") */
	RIGCTL_PATIENT_PRESS,   /* the assistant's hand at the site NAME */
	RIGCTL_PATIENT_RELEASE, /* lets go (NAME unused) */
};

/* The patient's command WHAT with NAME. Returns 0 or a negative errno; the
 * outcome in rigctl_said(). */
int rigctl_patient(struct rigctl *r, enum rigctl_patient what,
		   const char *name, uint64_t now_ns);

/* Sends CMD. Returns 0 or a negative errno; the outcome in rigctl_said(). */
int rigctl_command(struct rigctl *r, enum rigctl_command cmd,
		   uint64_t now_ns);

/*
 * Who trains at the rig, asked when RIGCTL_TRAINEE_POLL_S have passed
 * since the last ask (or at once after rigctl_trainee_now(), a login or a
 * logout): 1 asked now, *ASKS (the accounts hold a trainee: the form
 * asks) and TRAINEE (SIZE bytes; "": nobody) filled in; 0 not due; or a
 * negative errno (no answer). Blocks up to RIGCTL_TIMEOUT_MS.
 */
int rigctl_trainee(struct rigctl *r, uint64_t now_ns, bool *asks,
		   char *trainee, size_t size);
void rigctl_trainee_now(struct rigctl *r);

/*
 * NAME logs in with PIN to train at the rig (Login with training), or who
 * trains logs out (Logout), on the read-write socket, waiting up to
 * RIGCTL_LOGIN_TIMEOUT_MS: 0 (a login: who trains now into TRAINEE, SIZE
 * bytes), -EACCES refused, or another negative errno; either way WORDS
 * (SIZE bytes) says why, and rigctl_said() the outcome.
 */
int rigctl_login(struct rigctl *r, const char *name, const char *pin,
		 uint64_t now_ns, char *trainee, char *words, size_t size);
int rigctl_logout(struct rigctl *r, uint64_t now_ns, char *words,
		  size_t size);

/* Why the viewer cannot command (empty when it can). */
const char *rigctl_problem(const struct rigctl *r);

/* The reply to the last command, in words ("enabled", "refused: ..."). */
const char *rigctl_said(const struct rigctl *r);

/* True while hand input goes through. */
bool rigctl_driving(const struct rigctl *r);

#endif
