/* posture.c - see posture.h. */
#include "model/posture.h"

#include <errno.h>
#include <math.h>
#include <string.h>

#include "proto/endosim_shm.h"
#include "proto/names.h"

_Static_assert((int)POSTURE_LEFT_LATERAL ==
		       (int)ENDOSIM_POSITION_LEFT_LATERAL &&
	       (int)POSTURE_SUPINE == (int)ENDOSIM_POSITION_SUPINE &&
	       (int)POSTURE_RIGHT_LATERAL ==
		       (int)ENDOSIM_POSITION_RIGHT_LATERAL &&
	       (int)POSTURE_PRONE == (int)ENDOSIM_POSITION_PRONE,
	       "posture: the positions are the published ones");

/* Gravity's angle about z from +x: left lateral 0, supine pi/2 (+y),
 * right lateral pi, prone -pi/2 (3 pi/2). */
static double angle_of(int position)
{
	return position == POSTURE_PRONE ? -M_PI / 2 : position * M_PI / 2;
}

static void set_down(struct posture *p, double rad)
{
	p->down[0] = cos(rad);
	p->down[1] = sin(rad);
	p->down[2] = 0;
}

void posture_reset(struct posture *p, int position)
{
	memset(p, 0, sizeof(*p));
	p->position = p->from = position;
	p->from_rad = p->to_rad = angle_of(position);
	set_down(p, p->to_rad);
}

int posture_turn(struct posture *p, int position, double turn_s)
{
	double now = atan2(p->down[1], p->down[0]), d;

	if (position < 0 || position >= POSTURE_POSITIONS ||
	    !(turn_s >= 0)) {
		return -EINVAL;
	}
	/* the shorter way; half a turn from a lateral position over the
	 * back (through +y, supine), from supine or prone through the left
	 * lateral */
	d = remainder(angle_of(position) - now, 2 * M_PI);
	if (fabs(fabs(d) - M_PI) < 1e-6) {
		d = fabs(cos(now)) > 0.5 ? (cos(now) > 0 ? M_PI : -M_PI)
					 : (sin(now) > 0 ? -M_PI : M_PI);
	}
	p->from = p->position;
	p->position = position;
	p->from_rad = now;
	p->to_rad = now + d;
	p->turn_s = turn_s;
	p->elapsed_s = 0;
	if (turn_s <= 0) {
		set_down(p, p->to_rad);
	}
	return 0;
}

double posture_progress(const struct posture *p)
{
	return p->turn_s > 0 ? fmin(1, p->elapsed_s / p->turn_s) : 1;
}

void posture_step(struct posture *p, double dt_s)
{
	double u, e;

	if (!posture_turning(p)) {
		return;
	}
	p->elapsed_s += dt_s;
	u = posture_progress(p);
	e = u * u * (3 - 2 * u);
	set_down(p, p->from_rad + (p->to_rad - p->from_rad) * e);
}

bool posture_turning(const struct posture *p)
{
	return p->turn_s > 0 && p->elapsed_s < p->turn_s * (1 - 1e-9);
}

const char *posture_name(int position)
{
	return position >= 0 ? names_position((uint32_t)position) : "?";
}

int posture_find(const char *name)
{
	return names_position_find(name);
}
