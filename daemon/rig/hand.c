/* hand.c - see hand.h. */
#include "rig/hand.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "proto/seqlock.h"

/* The live input: the forces and the valves, each with its own hold (a
 * valves-only input leaves the forces' as they are). */
struct live {
	double force[ENDOSIM_AXES];
	uint64_t until_ns;        /* the forces hold until then */
	uint32_t valves;
	uint64_t valves_until_ns; /* the valves hold until then */
	uint32_t released;        /* hand_release()s so far */
	double tool_depth_m;      /* the tool's (tool.h) */
	double tool_opening;
	bool tool_pedal;
	uint64_t tool_until_ns;   /* the tool holds until then */
};

struct hand {
	double stiffness[ENDOSIM_AXES];
	double damping[ENDOSIM_AXES];
	double max[ENDOSIM_AXES];
	double max_speed[ENDOSIM_AXES];
	double grip_max[ENDOSIM_AXES];
	struct scenario *scenario;
	seqlock_t lock;       /* guards mailbox */
	struct live mailbox;  /* written by the control thread */
	struct live cached;   /* the force loop's last good copy */
	struct scenario_patient patient; /* the last handed out */
	/* the grip, the force loop's */
	bool held[ENDOSIM_AXES];
	double hold_at[ENDOSIM_AXES]; /* m or rad: where it holds */
	uint32_t released;            /* the last release taken */
};

struct hand *hand_create(const struct config *cfg, struct scenario *scn)
{
	struct hand *h = calloc(1, sizeof(*h));

	if (!h) {
		return NULL;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		h->stiffness[a] = cfg->sim.hand_stiffness[a];
		h->damping[a] = cfg->sim.hand_damping[a];
		h->max[a] = cfg->sim.hand_max[a];
		h->max_speed[a] = cfg->sim.hand_max_speed[a];
		h->grip_max[a] = cfg->sim.grip_max[a];
	}
	h->scenario = scn;
	seqlock_init(&h->lock);
	return h;
}

void hand_destroy(struct hand *h)
{
	if (!h) {
		return;
	}
	scenario_destroy(h->scenario);
	free(h);
}

const struct scenario *hand_scenario(const struct hand *h)
{
	return h->scenario;
}

void hand_set_live(struct hand *h, const double force[ENDOSIM_AXES],
		   uint32_t valves, double hold_s, uint64_t now_ns)
{
	uint64_t until = now_ns + (uint64_t)(hold_s * ENDOSIM_NS_PER_S);

	seqlock_write_begin(&h->lock);
	for (int a = 0; force && a < ENDOSIM_AXES; a++) {
		h->mailbox.force[a] = force[a];
	}
	if (force) {
		h->mailbox.until_ns = until;
	}
	h->mailbox.valves = valves;
	h->mailbox.valves_until_ns = until;
	seqlock_write_end(&h->lock);
}

void hand_set_tool(struct hand *h, double depth_m, double opening, bool pedal,
		   double hold_s, uint64_t now_ns)
{
	seqlock_write_begin(&h->lock);
	h->mailbox.tool_depth_m = depth_m;
	h->mailbox.tool_opening = opening;
	h->mailbox.tool_pedal = pedal;
	h->mailbox.tool_until_ns = now_ns + (uint64_t)(hold_s *
						       ENDOSIM_NS_PER_S);
	seqlock_write_end(&h->lock);
}

void hand_release(struct hand *h)
{
	seqlock_write_begin(&h->lock);
	h->mailbox.released++;
	seqlock_write_end(&h->lock);
}

/* One try: a writer caught mid-update leaves the previous copy in use. */
static void fetch_live(struct hand *h)
{
	uint64_t seq = seqlock_read_begin(&h->lock);
	struct live copy = h->mailbox;

	if (!seqlock_read_retry(&h->lock, seq)) {
		h->cached = copy;
	}
}

static double clamp(double v, double lim)
{
	return fmin(fmax(v, -lim), lim);
}

/*
 * What a hand can push with at speed V: its strength LIM, fading to
 * nothing at its top speed VMAX along the push (a muscle's force-velocity
 * curve, linearised); braking, it holds its full strength.
 */
static double muscle(double f, double v, double lim, double vmax)
{
	f = clamp(f, lim);
	if (f * v > 0) {
		f *= fmax(0.0, 1.0 - fabs(v) / vmax);
	}
	return f;
}

/* Axis A held where the hand left it: the spring to there, the place
 * slipping with the axis beyond the grip's strength. */
static double grip(struct hand *h, int a, double pos, double vel)
{
	double k = h->stiffness[a], reach = k > 0 ? h->grip_max[a] / k : 0;
	double off = h->hold_at[a] - pos;

	if (fabs(off) > reach) {
		h->hold_at[a] = pos + copysign(reach, off);
		off = h->hold_at[a] - pos;
	}
	return clamp(k * off - h->damping[a] * vel, h->grip_max[a]);
}

void hand_forces(struct hand *h, double t_s, uint64_t now_ns,
		 const double pos[ENDOSIM_AXES], const double vel[ENDOSIM_AXES],
		 double force[ENDOSIM_AXES])
{
	struct scenario_cmd cmd[ENDOSIM_AXES];

	fetch_live(h);
	if (h->cached.released != h->released) {
		h->released = h->cached.released;
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			h->held[a] = false;
		}
	}
	if (now_ns < h->cached.until_ns) {
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			force[a] = muscle(h->cached.force[a], vel[a], h->max[a],
					  h->max_speed[a]);
			h->held[a] = true; /* where the input leaves it */
			h->hold_at[a] = pos[a];
		}
		return;
	}
	if (!h->scenario || scenario_done(h->scenario, t_s)) {
		bool holds = false;

		for (int a = 0; a < ENDOSIM_AXES; a++) {
			holds |= h->held[a];
		}
		for (int a = 0; holds && a < ENDOSIM_AXES; a++) {
			force[a] = h->held[a] ? grip(h, a, pos[a], vel[a]) : 0;
		}
		if (holds) {
			return;
		}
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		cmd[a].mode = SCENARIO_FREE;
	}
	if (h->scenario) {
		scenario_eval(h->scenario, t_s, cmd);
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double f = 0;

		if (cmd[a].mode == SCENARIO_TARGET) {
			f = h->stiffness[a] * (cmd[a].value - pos[a]) -
			    h->damping[a] * vel[a];
		} else if (cmd[a].mode == SCENARIO_FORCE) {
			f = cmd[a].value;
		}
		force[a] = muscle(f, vel[a], h->max[a], h->max_speed[a]);
	}
}

uint32_t hand_valves(const struct hand *h, double t_s, uint64_t now_ns)
{
	if (now_ns < h->cached.valves_until_ns) {
		return h->cached.valves;
	}
	return h->scenario ? scenario_valves(h->scenario, t_s) : 0;
}

void hand_tool(const struct hand *h, uint64_t now_ns, double *depth_m,
	       double *opening, bool *pedal)
{
	bool live = now_ns < h->cached.tool_until_ns;

	*depth_m = live ? h->cached.tool_depth_m : NAN;
	*opening = live ? h->cached.tool_opening : NAN;
	*pedal = live && h->cached.tool_pedal;
}

void hand_patient(struct hand *h, double t_s, struct scenario_patient *out)
{
	if (h->scenario &&
	    scenario_patient_due(h->scenario, t_s) > h->patient.seq) {
		scenario_patient_get(h->scenario, h->patient.seq + 1,
				     &h->patient);
	}
	*out = h->patient;
}
