/* inject.c - see inject.h. */
#include "loop/inject.h"

#include <errno.h>
#include <math.h>
#include <string.h>

static bool valid(int action, int axis, double value)
{
	if (action < INJECT_CLEAR || action > INJECT_NAN || axis < -1 ||
	    axis >= ENDOSIM_AXES) {
		return false;
	}
	return action != INJECT_NAN || (value >= ENDOSIM_STAGE_FEEDBACK &&
					 value <= ENDOSIM_STAGE_COMMAND);
}

int inject_start(struct inject *in, int action, int axis, double value,
		 uint64_t now_ns)
{
	if (!valid(action, axis, value)) {
		return -EINVAL;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		struct inject_axis *ia = &in->axis[a];

		if (axis >= 0 && a != axis) {
			continue;
		}
		if (action == INJECT_CLEAR) {
			memset(ia, 0, sizeof(*ia));
			continue;
		}
		ia->on |= 1u << action;
		ia->value[action] = value;
		if (action == INJECT_STALE) {
			ia->stale_ns = now_ns;
		}
	}
	return 0;
}

static bool has(const struct inject_axis *ia, int action)
{
	return ia->on & 1u << action;
}

/* A NaN at STAGE on this axis? */
static bool nan_at(const struct inject_axis *ia, int stage)
{
	return has(ia, INJECT_NAN) && (int)ia->value[INJECT_NAN] == stage;
}

void inject_feedback(const struct inject *in, struct rig_feedback *fb)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct inject_axis *ia = &in->axis[a];
		struct rig_axis_feedback *f = &fb->axis[a];

		if (!ia->on) {
			continue;
		}
		if (has(ia, INJECT_DRIVE_FAULT)) {
			f->status |= ENDOSIM_DRIVE_FAULT;
			f->fault_detail = (uint32_t)ia->value[INJECT_DRIVE_FAULT];
		}
		if (has(ia, INJECT_DRIVE_GONE)) {
			f->status &= ~(uint32_t)(ENDOSIM_DRIVE_PRESENT |
						 ENDOSIM_DRIVE_ENABLED);
		}
		if (has(ia, INJECT_BUS_ERROR)) {
			f->status |= ENDOSIM_DRIVE_BUS_ERROR;
		}
		if (has(ia, INJECT_STALE)) {
			f->stamp_ns = ia->stale_ns;
		}
		if (has(ia, INJECT_SPEED)) {
			f->velocity = ia->value[INJECT_SPEED];
		}
		if (has(ia, INJECT_POSITION)) {
			f->position = ia->value[INJECT_POSITION];
		}
		if (nan_at(ia, ENDOSIM_STAGE_FEEDBACK)) {
			f->position = NAN;
		}
	}
}

/* The rendering's contact force, poisoned while any axis asks for it. */
static void poison_haptics(struct inject *in,
			   struct endosim_haptics_state *haptics)
{
	bool want = false;

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		want |= nan_at(&in->axis[a], ENDOSIM_STAGE_HAPTICS);
	}
	if (want && !in->haptics_nan) {
		in->haptics_saved = haptics->f_static[0];
	} else if (!want && in->haptics_nan) {
		haptics->f_static[0] = in->haptics_saved;
	}
	in->haptics_nan = want;
	if (want) {
		haptics->f_static[0] = NAN;
	}
}

void inject_pipeline(struct inject *in, struct scope_pose *pose,
		     struct endosim_haptics_state *haptics,
		     double command[ENDOSIM_AXES])
{
	poison_haptics(in, haptics);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct inject_axis *ia = &in->axis[a];

		if (!ia->on) {
			continue;
		}
		if (nan_at(ia, ENDOSIM_STAGE_KINEMATICS)) {
			pose->tip[a % 3] = NAN;
		}
		if (has(ia, INJECT_FORCE)) {
			command[a] = ia->value[INJECT_FORCE];
		}
		if (nan_at(ia, ENDOSIM_STAGE_COMMAND)) {
			command[a] = NAN;
		}
	}
}
