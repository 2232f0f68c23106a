/*
 * rigctl.h - endoview's commands to endosimd over the read-write socket
 * (control.sock, the endosim group): the simulated hand's forces
 * (HandInput) and the handle's valves with them, the state machine
 * (enable, disable, estop, reset), guided replay's take-over, resume and
 * reset, and the patient's (Patient: a turn, the assistant's hand).
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
#include <stdint.h>

#include "proto/endosim_shm.h"

#define RIGCTL_RETRY_S 1.0
#define RIGCTL_TIMEOUT_MS 200

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

/* Why the viewer cannot command (empty when it can). */
const char *rigctl_problem(const struct rigctl *r);

/* The reply to the last command, in words ("enabled", "refused: ..."). */
const char *rigctl_said(const struct rigctl *r);

/* True while hand input goes through. */
bool rigctl_driving(const struct rigctl *r);

#endif
