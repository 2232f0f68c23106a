/* faults.c - see faults.h. */
#include "loop/faults.h"

#include <stdio.h>

#include "proto/names.h"

static const char *const stage_names[] = {
	[ENDOSIM_STAGE_FEEDBACK] = "rig's feedback",
	[ENDOSIM_STAGE_KINEMATICS] = "scope's pose",
	[ENDOSIM_STAGE_HAPTICS] = "haptic rendering",
	[ENDOSIM_STAGE_COMMAND] = "force command",
	[ENDOSIM_STAGE_OUTPUT] = "setpoint after the safety filter",
};

const char *faults_stage_name(uint32_t stage)
{
	return stage >= ENDOSIM_STAGE_FEEDBACK && stage <= ENDOSIM_STAGE_OUTPUT
		       ? stage_names[stage] : "force pipeline";
}

void faults_describe(struct rig *rig, uint32_t bit,
		     const struct endosim_fault_cause *c, char *buf,
		     size_t size)
{
	const char *pos = names_axis_position_unit(c->axis);
	const char *force = names_axis_force_unit(c->axis);

	switch (bit) {
	case ENDOSIM_FAULT_OVERRUN:
		snprintf(buf, size, "the force loop skipped %.0f periods within "
			 "%.3g s, more than its budget of %.0f", c->value,
			 c->detail / 1e3, c->limit);
		return;
	case ENDOSIM_FAULT_TRAVEL:
		snprintf(buf, size, "position %.4g %s is beyond the end of "
			 "travel %.4g %s", c->value, pos, c->limit, pos);
		return;
	case ENDOSIM_FAULT_RUNAWAY:
		snprintf(buf, size, "speed %.4g %s/s is above the limit %.4g "
			 "%s/s: a runaway", c->value, pos, c->limit, pos);
		return;
	case ENDOSIM_FAULT_SATURATION:
		snprintf(buf, size, "force %.4g %s held beyond the limit %.4g %s "
			 "for %.2f s", c->value, force, c->limit, force,
			 c->detail / 1e3);
		return;
	case ENDOSIM_FAULT_NONFINITE:
		snprintf(buf, size, "%g in the %s", c->value,
			 faults_stage_name(c->detail));
		return;
	case ENDOSIM_FAULT_INTERNAL:
		snprintf(buf, size, "the control thread ended: no sockets; "
			 "endosimd stops");
		return;
	case ENDOSIM_FAULT_ESTOP:
		snprintf(buf, size, "emergency stop commanded");
		return;
	}
	rig_describe(rig, bit, c->axis, c->detail, buf, size);
}

void faults_format(struct rig *rig, uint64_t start_ns, uint32_t bit,
		   const struct endosim_fault_cause *c, char *buf,
		   size_t size)
{
	char what[400];

	faults_describe(rig, bit, c, what, sizeof(what));
	snprintf(buf, size, "%s%s%s (detail %u) at %.3f s: %s",
		 names_fault(bit), c->axis >= 0 ? " on " : "",
		 c->axis >= 0 ? names_axis(c->axis) : "", c->detail,
		 (double)(c->first_ns - start_ns) / ENDOSIM_NS_PER_S, what);
}
