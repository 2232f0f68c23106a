/*
 * rig_sim.c - the simulated rig: four plants (plant.h) moved by the motor
 * setpoints and the simulated hand (hand.h), integrated one loop period per
 * cycle. Simulated time advances by exactly one period per cycle, so a run
 * is repeatable whatever the machine's timing.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/log.h"
#include "model/plant.h"
#include "rig/rig_sim.h"

struct rig_sim {
	struct rig rig;
	struct plant plant[ENDOSIM_AXES];
	struct hand *hand;
	double hand_force[ENDOSIM_AXES]; /* N or N m, last step */
	double dt_s;                     /* loop period */
	double t_s;                      /* simulated time */
	bool enabled;                    /* torque was on in the last write */
};

static struct rig_sim *to_sim(struct rig *rig)
{
	return (struct rig_sim *)rig;
}

static int sim_start(struct rig *rig)
{
	(void)rig;
	return 0;
}

static void sim_read(struct rig *rig, uint64_t now_ns, struct rig_feedback *fb)
{
	struct rig_sim *s = to_sim(rig);
	const struct scenario *scn = hand_scenario(s->hand);

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		struct rig_axis_feedback *f = &fb->axis[a];

		f->position = s->plant[a].x;
		f->velocity = s->plant[a].v;
		f->hand = s->hand_force[a];
		/* the plants live in this thread: their state is current */
		f->stamp_ns = now_ns;
		f->status = ENDOSIM_DRIVE_PRESENT |
			    (s->enabled ? ENDOSIM_DRIVE_ENABLED : 0);
		f->fault_detail = 0;
	}
	fb->hand_time_s = s->t_s;
	fb->hand_done = scn && scenario_done(scn, s->t_s);
	fb->valves = hand_valves(s->hand, s->t_s, now_ns);
	hand_tool(s->hand, now_ns, &fb->tool_depth_m, &fb->tool_opening,
		  &fb->tool_pedal);
	hand_patient(s->hand, s->t_s, &fb->patient);
}

static void sim_write(struct rig *rig, uint64_t now_ns,
		      const double setpoint[ENDOSIM_AXES], bool enable)
{
	struct rig_sim *s = to_sim(rig);
	double pos[ENDOSIM_AXES], vel[ENDOSIM_AXES];

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		pos[a] = s->plant[a].x;
		vel[a] = s->plant[a].v;
	}
	hand_forces(s->hand, s->t_s, now_ns, pos, vel, s->hand_force);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double motor = enable ? setpoint[a] : 0.0;

		plant_step(&s->plant[a], motor + s->hand_force[a], s->dt_s);
	}
	s->t_s += s->dt_s;
	s->enabled = enable;
}

static void sim_stop(struct rig *rig)
{
	(void)rig;
}

static int sim_bus_stats(struct rig *rig, int index,
			 struct rig_bus_stats *st)
{
	(void)rig;
	(void)index;
	(void)st;
	return -ENOENT;
}

static void sim_describe(struct rig *rig, uint32_t fault_bit, int axis,
			 uint32_t detail, char *buf, size_t size)
{
	(void)rig;
	(void)axis;
	switch (fault_bit) {
	case ENDOSIM_FAULT_DRIVE:
		snprintf(buf, size, "simulated axis: drive fault 0x%04x",
			 detail);
		return;
	case ENDOSIM_FAULT_DRIVE_GONE:
		snprintf(buf, size, "simulated axis: device gone");
		return;
	case ENDOSIM_FAULT_STALE:
		snprintf(buf, size, "simulated axis: no feedback for %u ms",
			 detail);
		return;
	case ENDOSIM_FAULT_BUS:
		snprintf(buf, size, "simulated axis: a transaction failed");
		return;
	}
	snprintf(buf, size, "simulated axis");
}

static void sim_destroy(struct rig *rig)
{
	free(rig);
}

static const struct rig_ops sim_ops = {
	.name = "sim",
	.start = sim_start,
	.read = sim_read,
	.write = sim_write,
	.stop = sim_stop,
	.bus_stats = sim_bus_stats,
	.describe = sim_describe,
	.destroy = sim_destroy,
};

struct rig *rig_sim_create(const struct config *cfg, struct hand *hand)
{
	struct rig_sim *s = calloc(1, sizeof(*s));

	if (!s) {
		log_err("simulated rig: out of memory");
		return NULL;
	}
	s->rig.ops = &sim_ops;
	s->hand = hand;
	s->dt_s = 1.0 / cfg->loop.rate_hz;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		struct plant_params p = {
			.inertia = cfg->sim.inertia[a],
			.viscous = cfg->sim.viscous[a],
			.coulomb = cfg->sim.coulomb[a],
			.min = cfg->rig.travel_min[a],
			.max = cfg->rig.travel_max[a],
		};

		plant_init(&s->plant[a], &p, 0.0);
	}
	return &s->rig;
}
