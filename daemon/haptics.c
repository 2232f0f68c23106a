/* haptics.c - see haptics.h. */
#include "haptics.h"

#include <math.h>

/*
 * The brake near the ends: depth into the zone (0..1) times LIMIT, scaled by
 * the speed towards the end up to the speed that crosses the zone in one
 * second (a smooth, saturating damper, so the force does not chatter as the
 * velocity passes zero).
 */
static double end_brake(double x, double v, double min, double max,
			double zone, double limit)
{
	double width = zone * (max - min);
	double depth = 0.0;

	if (v > 0 && x > max - width) {
		depth = (x - (max - width)) / width;
	} else if (v < 0 && x < min + width) {
		depth = ((min + width) - x) / width;
	}
	return -limit * fmin(depth, 1.0) * fmin(fabs(v) / width, 1.0) *
	       (v > 0 ? 1.0 : -1.0);
}

void haptics_render(const struct config *cfg, const struct rig_feedback *fb,
		    double command[ENDOSIM_AXES])
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct rig_axis_feedback *f = &fb->axis[a];

		command[a] = end_brake(f->position, f->velocity,
				       cfg->rig.travel_min[a],
				       cfg->rig.travel_max[a],
				       cfg->haptics.end_zone,
				       cfg->limits.max[a]) -
			     cfg->haptics.damping[a] * f->velocity;
	}
}
