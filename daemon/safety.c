/* safety.c - see safety.h. */
#include "safety.h"

#include <errno.h>
#include <math.h>

void safety_init(struct safety *s)
{
	*s = (struct safety){ .state = ENDOSIM_STATE_IDLE, .fault_axis = -1 };
}

int safety_command(struct safety *s, enum safety_cmd cmd)
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
		s->state = ENDOSIM_STATE_ESTOP;
		return 0;
	case SAFETY_RESET:
		if (s->active) {
			return -EBUSY;
		}
		if (s->state != ENDOSIM_STATE_ENABLED) {
			s->state = ENDOSIM_STATE_IDLE;
		}
		s->faults = 0;
		s->fault_bit = 0;
		s->fault_axis = -1;
		s->fault_detail = 0;
		s->fault_ns = 0;
		return 0;
	}
	return -EINVAL;
}

void safety_begin_cycle(struct safety *s)
{
	s->active = s->seen;
	s->seen = 0;
}

void safety_fault(struct safety *s, uint32_t bit, int axis, uint32_t detail,
		  uint64_t now_ns)
{
	int k = __builtin_ctz(bit);

	s->seen |= bit;
	if (!(s->faults & bit)) {
		s->cause[k] = (struct safety_cause){ axis, detail };
	}
	if (!s->faults) {
		s->fault_bit = bit;
		s->fault_axis = axis;
		s->fault_detail = detail;
		s->fault_ns = now_ns;
	}
	s->faults |= bit;
	s->state = ENDOSIM_STATE_FAULT;
}

static bool finite_axis(const struct rig_axis_feedback *f)
{
	return isfinite(f->position) && isfinite(f->velocity);
}

void safety_check_feedback(struct safety *s, const struct config *cfg,
			   const struct rig_feedback *fb, uint64_t now_ns)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct rig_axis_feedback *f = &fb->axis[a];
		uint64_t max_age =
			(uint64_t)(config_feedback_max_age_s(cfg, a) * 1e9);

		if (!(f->status & ENDOSIM_DRIVE_PRESENT)) {
			safety_fault(s, ENDOSIM_FAULT_DRIVE_GONE, a,
				     f->fault_detail, now_ns);
		} else if (f->status & ENDOSIM_DRIVE_FAULT) {
			safety_fault(s, ENDOSIM_FAULT_DRIVE, a, f->fault_detail,
				     now_ns);
		} else if (f->status & ENDOSIM_DRIVE_BUS_ERROR) {
			safety_fault(s, ENDOSIM_FAULT_BUS, a, f->fault_detail,
				     now_ns);
		} else if (now_ns > f->stamp_ns &&
			   now_ns - f->stamp_ns > max_age) {
			safety_fault(s, ENDOSIM_FAULT_STALE, a,
				     (uint32_t)((now_ns - f->stamp_ns) / 1000000),
				     now_ns);
		}
		if (!finite_axis(f)) {
			safety_fault(s, ENDOSIM_FAULT_NONFINITE, a, 0, now_ns);
		}
	}
}

bool safety_torque_on(const struct safety *s)
{
	return s->state == ENDOSIM_STATE_ENABLED;
}

void safety_filter(struct safety *s, const struct config *cfg,
		   const double command[ENDOSIM_AXES],
		   double limited[ENDOSIM_AXES], double dt_s, uint64_t now_ns)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (!isfinite(command[a])) {
			safety_fault(s, ENDOSIM_FAULT_NONFINITE, a, 0, now_ns);
		}
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double lim = cfg->limits.max[a];
		double step = cfg->limits.slew[a] * dt_s;
		double want = fmin(fmax(command[a], -lim), lim);

		limited[a] = safety_torque_on(s)
				     ? fmin(fmax(want, limited[a] - step),
					    limited[a] + step)
				     : 0.0;
	}
}
