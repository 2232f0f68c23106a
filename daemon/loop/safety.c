/* safety.c - see safety.h. */
#include "loop/safety.h"

#include <errno.h>
#include <math.h>
#include <string.h>

void safety_init(struct safety *s)
{
	memset(s, 0, sizeof(*s));
	s->state = ENDOSIM_STATE_IDLE;
}

/* Latches BIT like a fault, keeping the state. */
static void latch(struct safety *s, uint32_t bit,
		  const struct endosim_fault_cause *c)
{
	int k = __builtin_ctz(bit);

	s->seen |= bit;
	if (s->faults & bit) {
		return;
	}
	s->cause[k] = *c;
	s->faults |= bit;
	s->latched++;
	if (!s->fault_bit) {
		s->fault_bit = bit;
	}
}

static void clear(struct safety *s)
{
	s->faults = 0;
	s->fault_bit = 0;
	memset(s->cause, 0, sizeof(s->cause));
}

int safety_command(struct safety *s, enum safety_cmd cmd, uint64_t now_ns)
{
	switch (cmd) {
	case SAFETY_ENABLE:
		if (s->state == ENDOSIM_STATE_FAULT ||
		    s->state == ENDOSIM_STATE_ESTOP) {
			return -EPERM;
		}
		s->state = ENDOSIM_STATE_ENABLED;
		return 0;
	case SAFETY_DISABLE:
		if (s->state == ENDOSIM_STATE_ENABLED) {
			s->state = ENDOSIM_STATE_IDLE;
		}
		return 0;
	case SAFETY_ESTOP:
		latch(s, ENDOSIM_FAULT_ESTOP,
		      &(struct endosim_fault_cause){ .first_ns = now_ns,
						     .axis = -1 });
		s->seen &= ~ENDOSIM_FAULT_ESTOP; /* its cause is a command */
		s->state = ENDOSIM_STATE_ESTOP;
		return 0;
	case SAFETY_RESET:
		if (s->active) {
			return -EBUSY;
		}
		if (s->state != ENDOSIM_STATE_ENABLED) {
			s->state = ENDOSIM_STATE_IDLE;
		}
		clear(s);
		return 0;
	}
	return -EINVAL;
}

void safety_begin_cycle(struct safety *s)
{
	s->active = s->seen;
	s->seen = 0;
}

void safety_fault(struct safety *s, uint32_t bit,
		  const struct endosim_fault_cause *c)
{
	latch(s, bit, c);
	s->state = ENDOSIM_STATE_FAULT;
}

const struct endosim_fault_cause *safety_first(const struct safety *s)
{
	return s->fault_bit ? &s->cause[__builtin_ctz(s->fault_bit)] : NULL;
}

/* A cause on AXIS with DETAIL, VALUE and LIMIT. */
static void fault(struct safety *s, uint32_t bit, int axis, uint32_t detail,
		  double value, double limit, uint64_t now_ns)
{
	struct endosim_fault_cause c = {
		.first_ns = now_ns, .axis = axis, .detail = detail,
		.value = value, .limit = limit,
	};

	safety_fault(s, bit, &c);
}

void safety_check_finite(struct safety *s, const double *v, size_t n,
			 int axis, uint32_t stage, uint64_t now_ns)
{
	for (size_t i = 0; i < n; i++) {
		if (!isfinite(v[i])) {
			fault(s, ENDOSIM_FAULT_NONFINITE, axis, stage, v[i], 0,
			      now_ns);
			return;
		}
	}
}

void safety_check_feedback(struct safety *s, const struct config *cfg,
			   const struct rig_feedback *fb, uint64_t now_ns)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct rig_axis_feedback *f = &fb->axis[a];
		double max_age_s = config_feedback_max_age_s(cfg, a);
		uint64_t max_age = (uint64_t)(max_age_s * ENDOSIM_NS_PER_S);
		double v[3] = { f->position, f->velocity, f->hand };

		if (!(f->status & ENDOSIM_DRIVE_PRESENT)) {
			fault(s, ENDOSIM_FAULT_DRIVE_GONE, a, f->fault_detail, 0,
			      0, now_ns);
		} else if (f->status & ENDOSIM_DRIVE_FAULT) {
			fault(s, ENDOSIM_FAULT_DRIVE, a, f->fault_detail, 0, 0,
			      now_ns);
		} else if (f->status & ENDOSIM_DRIVE_BUS_ERROR) {
			fault(s, ENDOSIM_FAULT_BUS, a, f->fault_detail, 0, 0,
			      now_ns);
		} else if (now_ns > f->stamp_ns &&
			   now_ns - f->stamp_ns > max_age) {
			double age_s = (double)(now_ns - f->stamp_ns) /
				       ENDOSIM_NS_PER_S;

			fault(s, ENDOSIM_FAULT_STALE, a,
			      (uint32_t)(age_s * 1e3), age_s, max_age_s, now_ns);
		}
		safety_check_finite(s, v, 3, a, ENDOSIM_STAGE_FEEDBACK, now_ns);
	}
}

void safety_check_motion(struct safety *s, const struct config *cfg,
			 const struct rig_feedback *fb, uint64_t now_ns)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double x = fb->axis[a].position, v = fb->axis[a].velocity;
		double lo = cfg->rig.travel_min[a], hi = cfg->rig.travel_max[a];
		double margin = cfg->limits.travel_margin * (hi - lo);
		double vmax = cfg->limits.max_speed[a];

		s->speed[a] = isfinite(v) ? v : 0.0;
		if (x < lo - margin) {
			fault(s, ENDOSIM_FAULT_TRAVEL, a, 0, x, lo - margin,
			      now_ns);
		} else if (x > hi + margin) {
			fault(s, ENDOSIM_FAULT_TRAVEL, a, 0, x, hi + margin,
			      now_ns);
		}
		if (fabs(v) > vmax) {
			fault(s, ENDOSIM_FAULT_RUNAWAY, a, 0, v, vmax, now_ns);
		}
	}
}

/* Records SKIPPED at NOW_NS; returns the periods skipped within the window. */
static uint64_t overrun_window(struct safety *s, const struct config *cfg,
			       uint64_t skipped, uint64_t now_ns)
{
	uint32_t size = (uint32_t)cfg->loop.overrun_budget + 1;
	uint64_t window =
		(uint64_t)(cfg->loop.overrun_window_s * ENDOSIM_NS_PER_S);
	uint64_t n = 0;

	if (size != s->overrun_size) { /* a new budget: start afresh */
		memset(s->overrun, 0, sizeof(s->overrun));
		s->overrun_size = size;
		s->overrun_next = 0;
	}
	if (skipped) {
		s->overrun[s->overrun_next].ns = now_ns;
		s->overrun[s->overrun_next].n = skipped;
		s->overrun_next = (s->overrun_next + 1) % size;
	}
	/* newest first; each overrun skipped one period at least, so a ring
	 * of budget + 1 holds every overrun of a window within the budget */
	for (uint32_t i = 1; i <= size; i++) {
		uint32_t k = (s->overrun_next + size - i) % size;

		if (!s->overrun[k].n || now_ns - s->overrun[k].ns > window) {
			break;
		}
		n += s->overrun[k].n;
	}
	return n;
}

bool safety_check_overruns(struct safety *s, const struct config *cfg,
			   uint64_t skipped, uint64_t now_ns)
{
	uint64_t budget = (uint64_t)cfg->loop.overrun_budget;
	bool was_over = s->overrun_window > budget;

	s->overrun_window = overrun_window(s, cfg, skipped, now_ns);
	s->overrun_warning = false;
	if (s->overrun_window <= budget) {
		return false;
	}
	if (!was_over) {
		s->overrun_misses++;
	}
	if (config_overrun_faults(cfg)) {
		fault(s, ENDOSIM_FAULT_OVERRUN, -1,
		      (uint32_t)(cfg->loop.overrun_window_s * 1e3),
		      (double)s->overrun_window, (double)budget, now_ns);
		return false;
	}
	s->overrun_warning = true;
	return !was_over;
}

bool safety_torque_on(const struct safety *s)
{
	return s->state == ENDOSIM_STATE_ENABLED;
}

/* The enable ramp this cycle: 0 when torque is off, then up to 1. */
static double ramp(struct safety *s, const struct config *cfg,
		   uint64_t now_ns)
{
	bool on = safety_torque_on(s);
	double t;

	if (on && !s->torque_was_on) {
		s->enabled_ns = now_ns;
	}
	s->torque_was_on = on;
	if (!on) {
		return 0.0;
	}
	t = (double)(now_ns - s->enabled_ns) / ENDOSIM_NS_PER_S;
	return cfg->limits.enable_ramp_s > 0
		       ? fmin(t / cfg->limits.enable_ramp_s, 1.0) : 1.0;
}

/* Times how long AXIS has been held beyond LIM; faults past the limit. */
static void check_saturation(struct safety *s, const struct config *cfg,
			     int axis, double force, double lim,
			     uint64_t now_ns)
{
	uint64_t *since = &s->saturated_since[axis];
	double held_s;

	if (!safety_torque_on(s) || fabs(force) <= lim) {
		*since = 0;
		return;
	}
	if (!*since) {
		*since = now_ns;
	}
	held_s = (double)(now_ns - *since) / ENDOSIM_NS_PER_S;
	if (held_s <= cfg->limits.saturation_s) {
		return;
	}
	if (config_saturation_faults(cfg, axis)) {
		fault(s, ENDOSIM_FAULT_SATURATION, axis,
		      (uint32_t)(held_s * 1e3), force, lim, now_ns);
	} else {
		s->saturation_warning = true;
	}
}

void safety_filter(struct safety *s, const struct config *cfg,
		   const double command[ENDOSIM_AXES],
		   double limited[ENDOSIM_AXES], double dt_s, uint64_t now_ns)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		safety_check_finite(s, &command[a], 1, a,
				    ENDOSIM_STAGE_COMMAND, now_ns);
	}
	s->ramp = ramp(s, cfg, now_ns);
	s->saturation_warning = false;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double force = command[a] * s->ramp;

		check_saturation(s, cfg, a, force, cfg->limits.max[a], now_ns);
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double lim = cfg->limits.max[a];
		double step = cfg->limits.slew[a] * dt_s;
		double want = fmin(fmax(command[a] * s->ramp, -lim), lim);
		double v = s->speed[a], vmax = cfg->limits.max_speed[a];

		if (want * v > 0) { /* pushing the way it moves */
			double fade = (SAFETY_FADE_END - fabs(v) / vmax) /
				      (SAFETY_FADE_END - SAFETY_FADE_START);

			want *= fmin(fmax(fade, 0.0), 1.0);
		}

		limited[a] = safety_torque_on(s)
				     ? fmin(fmax(want, limited[a] - step),
					    limited[a] + step)
				     : 0.0;
	}
	safety_check_finite(s, limited, ENDOSIM_AXES, -1, ENDOSIM_STAGE_OUTPUT,
			    now_ns);
	if (!safety_torque_on(s)) {
		memset(limited, 0, sizeof(double) * ENDOSIM_AXES);
	}
}

void safety_publish(const struct safety *s, uint64_t now_ns,
		    struct endosim_safety_state *out)
{
	out->active = s->seen |
		      (s->overrun_warning ? ENDOSIM_FAULT_OVERRUN : 0) |
		      (s->saturation_warning ? ENDOSIM_FAULT_SATURATION : 0);
	out->overrun_periods = (uint32_t)s->overrun_window;
	out->enabled_ns = s->enabled_ns;
	out->ramp = safety_torque_on(s) ? s->ramp : 0.0;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		uint64_t since = s->saturated_since[a];

		out->saturated_s[a] =
			since ? (double)(now_ns - since) / ENDOSIM_NS_PER_S
			      : 0.0;
	}
	out->faults_latched = s->latched;
	memcpy(out->cause, s->cause, sizeof(out->cause));
}
