/*
 * haptics_private.h - inside the haptics (haptics.h): the struct that
 * haptics.c, the paper's model (haptics_paper.c) and the rod's
 * (haptics_rod.c) share, and the parts of haptics.c that both models
 * render with: the tip's god-object contact, its spring, the passivity
 * observer, the wheels' last parts. For those three files only.
 *
 * Force loop: nothing here allocates, blocks or prints. Units SI.
 */
#ifndef ENDOSIM_HAPTICS_PRIVATE_H
#define ENDOSIM_HAPTICS_PRIVATE_H

#include <stdbool.h>

#include "model/godobject.h"
#include "model/haptics.h"
#include "model/haptics_paper.h"
#include "model/haptics_rod.h"

struct haptics {
	enum haptics_model model;    /* which renders: gains.model */
	struct godobject go;         /* the tip's contact */
	bool fresh;                  /* place the proxy at the next tip */
	double proxy_s;              /* m: where along the colon it is */
	struct haptics_paper_loops loops; /* measured in either model */
	struct haptics_rod_tube rod; /* the rod model's */
	double energy[ENDOSIM_AXES]; /* passivity observers, J */
	double last_x[ENDOSIM_AXES]; /* axis positions last cycle */
	struct patient patient;      /* the body around the colon */
	double tip_force_n;          /* the wall's on the tip last cycle */
	double tip_gap_m;            /* its clearance to the wall then */
	double span_tension_n[ENDOSIM_SPANS]; /* each mobile span's
						 mesentery then, N */
};

/* The contact this cycle, in the colon's coordinates now. */
struct haptics_touch {
	bool on;
	int planes;
	double proxy[3];
	double normal[3];
	double force[3];    /* F_static, N */
	double spring[3];   /* its spring alone (the rod takes it on) */
	double depth;       /* m */
};

/*
 * The spring between proxy and tip: the wall's stiffness along the tip's
 * view direction DIR, and across it the wall in series with the bending
 * section's own lateral compliance (a real bending section gives way when
 * its side meets the wall; head-on, the tube does not). K = k_wall D D^T +
 * k_side (I - D D^T), k_side = k_wall k_lat / (k_wall + k_lat): OUT = K
 * DELTA.
 */
void haptics_spring(const struct haptics_params *par, const double dir[3],
		    const double delta[3], double out[3]);

/*
 * The tip's god-object contact this cycle (haptics.h) into T, the tip
 * moving at TIP_V (m/s, world: the rod's tip), or, NULL, as the axes'
 * velocities move it through the pose's Jacobian (the paper's
 * kinematics'); the proxy starts afresh where h->fresh says or the tip
 * is not yet in.
 */
void haptics_touch_wall(struct haptics *h, const struct haptics_input *in,
			const double tip_v[3], struct haptics_touch *t);

/* T's contact into OUT's proxy, normal, f_static, penetration, contact
 * and constraints. */
void haptics_publish_touch(const struct haptics_touch *t,
			   struct endosim_haptics_state *out);

/* Wheel axis A is turned by a drive behind a bus: its torque lags. */
bool haptics_wheel_lags(const struct haptics_params *par, int a);

/*
 * The stiffness wheel W can render behind its drive's lag, N m/rad: its
 * virtual damping over the lag (the period's hold and wheel_delay_s),
 * less what the bending section's spring already takes (haptics.h).
 */
double haptics_wheel_budget(const struct haptics_input *in, int w);

/*
 * Hannaford and Ryu's observer on axes FIRST.. (haptics.h): damping on
 * CONTACT (N, N m per axis) where the energy went negative; OUT's
 * passivity_damping (the insertion axis', N s/m) and passivity_energy_j
 * (every axis').
 */
void haptics_passivity(struct haptics *h, const struct haptics_input *in,
		       double contact[ENDOSIM_AXES], int first,
		       struct endosim_haptics_state *out);

/*
 * Both models' last parts: each wheel's (the contact's CONTACT, the wire
 * tension from OUT's wire_dl_m, the spring-back and the stop) and every
 * axis' damping, into OUT; the wheels' COMMAND, and the damping added to
 * every axis' (insertion's and roll's set before).
 */
void haptics_wheels_and_damping(const struct haptics_input *in,
				const double contact[ENDOSIM_AXES],
				struct endosim_haptics_state *out,
				double command[ENDOSIM_AXES]);

#endif
