/* tool.c - see tool.h. */
#include "model/tool.h"

#include <errno.h>
#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "model/centreline.h"
#include "model/colon.h"
#include "model/gas.h"

_Static_assert(ANATOMY_MAX_POLYPS == ENDOSIM_POLYPS,
	       "tool: every polyp of a case published");

/* Paris' limit of a IIa lesion's height over the mucosa, m. */
#define PARIS_IIA_MAX_M 0.0025

static double clamp01(double x)
{
	return x < 0 ? 0 : x > 1 ? 1 : x;
}

void tool_reset(struct tool *t)
{
	memset(t, 0, sizeof(*t));
	t->captured = -1;
	t->lying = -1;
}

/* The loop lets go of what it holds (the handle opened, another tool). */
static int release(struct tool *t)
{
	int i = t->captured;

	if (i >= 0) {
		t->polyp[i].state = TOOL_POLYP_IN_PLACE;
		t->captured = -1;
	}
	return i;
}

int tool_select(struct tool *t, int kind, double snare_m)
{
	if (kind < TOOL_NONE || kind > TOOL_CLIP) {
		return -EINVAL;
	}
	if (kind == TOOL_SNARE &&
	    !(snare_m >= TOOL_SNARE_MIN_M && snare_m <= TOOL_SNARE_MAX_M)) {
		return -EINVAL;
	}
	release(t);
	t->kind = kind;
	t->snare_m = kind == TOOL_SNARE ? snare_m : 0;
	t->command_m = 0;
	t->loop_m = 0;
	t->armed = false;
	for (int i = 0; i < t->polyps; i++) {
		t->polyp[i].inside = false;
	}
	return 0;
}

int tool_add_polyp(struct tool *t, const struct anatomy_polyp *ap,
		   const double base[3], const double normal[3])
{
	struct tool_polyp *p;
	double n[3];

	if (t->polyps == ANATOMY_MAX_POLYPS) {
		return -ENOSPC;
	}
	vec3_copy(n, normal);
	if (!(vec3_normalize(n) > 0)) {
		return -EINVAL;
	}
	p = &t->polyp[t->polyps];
	*p = (struct tool_polyp){
		.size_m = ap->diameter_m, .paris = ap->paris,
		.stalk_m = ap->paris == ANATOMY_PARIS_IP ?
			   ap->stalk_length_m : 0,
		.stalk_diameter_m = ap->paris == ANATOMY_PARIS_IP ?
				    ap->stalk_diameter_m : 0,
		.s_m = ap->s_m,
	};
	vec3_copy(p->base, base);
	vec3_copy(p->normal, n);
	return t->polyps++;
}

int tool_place_polyps(struct tool *t, const struct colon *c)
{
	const struct anatomy *a = colon_anatomy(c);
	int added = 0;

	for (int i = 0; a && i < a->polyps; i++) {
		const struct anatomy_polyp *ap = &a->polyp[i];
		struct centreline_point q;
		double r, out[3], base[3], n[3];
		int e;

		centreline_at_s(colon_centreline(c), ap->s_m, &q);
		r = colon_lumen_radius(c, ap->s_m, ap->angle_rad);
		vec3_scale(out, q.u, cos(ap->angle_rad));
		vec3_axpy(out, out, sin(ap->angle_rad), q.v);
		vec3_axpy(base, q.p, r, out);
		vec3_scale(n, out, -1);
		e = tool_add_polyp(t, ap, base, n);
		if (e < 0) {
			return e;
		}
		t->polyp[e].on_wall = true;
		t->polyp[e].angle_rad = ap->angle_rad;
		t->polyp[e].wall_r_m = r;
		added++;
	}
	return added;
}

void tool_wall(const struct colon *c, double s_m, const double tip[3],
	       const double *factor, struct tool_input *in)
{
	struct centreline_point q;
	double x[3], out[3], theta;

	in->wall = colon_anatomy(c) != NULL && isfinite(s_m);
	if (!in->wall) {
		return;
	}
	centreline_at_s(colon_centreline(c), s_m, &q);
	vec3_sub(x, tip, q.p);
	theta = atan2(vec3_dot(x, q.v), vec3_dot(x, q.u));
	vec3_scale(out, q.u, cos(theta));
	vec3_axpy(out, out, sin(theta), q.v);
	vec3_axpy(in->wall_point, q.p,
		  colon_lumen_radius(c, s_m, theta) *
			  (factor ? gas_factor_at(c, factor, s_m) : 1),
		  out);
	vec3_scale(in->wall_normal, out, -1);
}

void tool_follow_wall(struct tool *t, const struct colon *c,
		      const double *factor)
{
	for (int i = 0; i < t->polyps; i++) {
		struct tool_polyp *p = &t->polyp[i];
		struct centreline_point q;
		double out[3], f;

		if (!p->on_wall) {
			continue;
		}
		f = factor ? gas_factor_at(c, factor, p->s_m) : 1;
		centreline_at_s(colon_centreline(c), p->s_m, &q);
		vec3_scale(out, q.u, cos(p->angle_rad));
		vec3_axpy(out, out, sin(p->angle_rad), q.v);
		vec3_axpy(p->base, q.p, f * p->wall_r_m, out);
		vec3_scale(p->normal, out, -1);
	}
}

double tool_polyp_thickness(const struct tool_polyp *p)
{
	return p->paris == ANATOMY_PARIS_IP ? p->stalk_diameter_m : p->size_m;
}

double tool_polyp_height(const struct tool_polyp *p, double lift_m)
{
	double lift = p->lifted ? lift_m : 0;

	switch (p->paris) {
	case ANATOMY_PARIS_IP:
		return p->stalk_m;
	case ANATOMY_PARIS_IS:
		return p->size_m / 2 + lift;
	case ANATOMY_PARIS_IIA:
		return fmin(p->size_m / 4, PARIS_IIA_MAX_M) + lift;
	default:
		return lift;
	}
}

double tool_loop_diameter(double snare_m, double opening, double depth_m)
{
	double wire = clamp01(opening) * M_PI * snare_m / 2;

	if (depth_m < 0) {
		wire = fmax(0, wire + depth_m);
	}
	return fmin(snare_m, 2 * wire / M_PI);
}

void tool_pose(const struct tool_params *par,
	       const struct endosim_scope_state *sc, double depth_m,
	       struct tool_pose *out)
{
	double right[3];

	vec3_copy(out->dir, sc->dir);
	vec3_cross(right, sc->dir, sc->up);
	vec3_scale(out->radial, sc->up, cos(par->channel_angle_rad));
	vec3_axpy(out->radial, out->radial, sin(par->channel_angle_rad),
		  right);
	vec3_cross(out->side, out->dir, out->radial);
	vec3_axpy(out->exit, sc->tip, par->channel_offset_m, out->radial);
	vec3_axpy(out->tip, out->exit, depth_m, out->dir);
}

/* The loop hangs from the sheath's tip, its centre half its diameter on. */
static void place_loop(struct tool *t)
{
	vec3_axpy(t->loop_centre, t->pose.tip, t->loop_m / 2, t->pose.dir);
}

/*
 * Whether P's axis, H_M high, crosses the loop's plane; *Q_M then the
 * crossing's distance from the loop's centre.
 */
static bool crossing(const struct tool *t, const struct tool_polyp *p,
		     double h_m, double *q_m)
{
	double den = vec3_dot(p->normal, t->pose.radial), x[3], lambda;

	if (fabs(den) < 1e-9) {
		return false;
	}
	vec3_sub(x, t->loop_centre, p->base);
	lambda = vec3_dot(x, t->pose.radial) / den;
	if (lambda < 0 || lambda > h_m) {
		return false;
	}
	vec3_axpy(x, p->base, lambda, p->normal);
	*q_m = vec3_dist(x, t->loop_centre);
	return true;
}

/* The closing loop meets the polyps: the first whose axis was inside it
 * and which the wire reaches now is captured; each one's inside flag for
 * the next step. Returns the polyp captured, or -1. */
static int meet(struct tool *t, const struct tool_params *par, bool closing)
{
	int caught = -1;

	for (int i = 0; i < t->polyps; i++) {
		struct tool_polyp *p = &t->polyp[i];
		double h = tool_polyp_height(p, par->lift_m), q = 0;
		bool x = p->state == TOOL_POLYP_IN_PLACE && h > 0 &&
			 crossing(t, p, h, &q);

		if (closing && caught < 0 && t->captured < 0 && p->inside &&
		    x && q + tool_polyp_thickness(p) / 2 >= t->loop_m / 2) {
			caught = i;
		}
		p->inside = x && q < t->loop_m / 2;
	}
	if (caught >= 0) {
		t->polyp[caught].state = TOOL_POLYP_CAPTURED;
		t->polyp[caught].inside = false;
		t->captured = caught;
	}
	return caught;
}

/* The loop's circle reaches the wall's plane (within half the wire). */
static bool loop_on_wall(const struct tool *t, const struct tool_params *par,
			 const struct tool_input *in)
{
	double x[3], c = vec3_dot(t->pose.radial, in->wall_normal);

	vec3_sub(x, t->loop_centre, in->wall_point);
	return vec3_dot(x, in->wall_normal) -
	       t->loop_m / 2 * sqrt(fmax(0, 1 - c * c)) <= par->wire_m / 2;
}

/* P just cut: its stalk bleeds when it was not coagulated through. */
static unsigned start_bleed(struct tool_polyp *p,
			    const struct tool_params *par)
{
	double t = p->stalk_diameter_m, area = M_PI * t * t / 4;

	if (p->paris != ANATOMY_PARIS_IP || t < par->bleed_min_m ||
	    p->energy_j >= par->coag_j_per_m3 * area * t) {
		return 0;
	}
	p->bleed = TOOL_BLEED_BLEEDING;
	p->bleed_m3_s = tool_polyp_flow(p, par);
	p->bleed_s = 0;
	return TOOL_EVENT_BLEED;
}

void tool_polyp_body(const struct tool_polyp *p, const struct tool_params *par,
		     double at[3])
{
	double h = p->paris == ANATOMY_PARIS_IP ? p->stalk_m + p->size_m / 2
						: tool_polyp_height(p,
							par->lift_m) / 2;

	vec3_axpy(at, p->base, h, p->normal);
}

double tool_polyp_flow(const struct tool_polyp *p,
		       const struct tool_params *par)
{
	double t = p->stalk_diameter_m;

	return par->bleed_m_per_s * M_PI * t * t / 4;
}

/* P cut free where it stands: its body's centre (tool.h), at rest there
 * until its first rest is found (tool_fall()). */
static void come_free(struct tool_polyp *p, const struct tool_params *par)
{
	p->state = TOOL_POLYP_CUT;
	tool_polyp_body(p, par, p->at);
	vec3_copy(p->rest, p->at);
	vec3_set(p->rest_wall, 0, 0, 0);
	p->rest_ok = false;
	p->lies = false;
	p->fall_v = 0;
	p->moved = true;
}

/* The held polyp cut, hot or cold; TOOL_EVENT_* bits. */
static unsigned cut(struct tool *t, const struct tool_params *par,
		    bool pedal, double dt_s)
{
	struct tool_polyp *p = &t->polyp[t->captured];
	double th = tool_polyp_thickness(p);
	unsigned ev = 0;
	bool through;

	if (pedal) {
		p->energy_j += par->hot_power_w * dt_s;
		if (!p->lifted && p->paris != ANATOMY_PARIS_IP &&
		    !t->injured) {
			t->injured = true;
			vec3_copy(t->injury_at, p->base);
			ev |= TOOL_EVENT_INJURY;
		}
		through = p->energy_j >= par->cut_j_per_m2 * M_PI * th * th / 4;
	} else {
		through = t->opening <= par->closed_opening &&
			  th < par->cold_max_m;
	}
	if (through) {
		come_free(p, par);
		t->captured = -1;
		ev |= TOOL_EVENT_CUT | start_bleed(p, par);
	}
	return ev;
}

/* The snare's step after the pose; *WHICH the polyp concerned. */
static unsigned snare_step(struct tool *t, const struct tool_params *par,
			   const struct tool_input *in, bool pedal,
			   double dt_s, int *which)
{
	double cmd = tool_loop_diameter(t->snare_m, t->opening, t->depth_m);
	bool closing = cmd < t->command_m, opening = cmd > t->command_m;
	unsigned ev = 0;
	int i = t->captured;

	t->command_m = cmd;
	if (i >= 0 && opening && cmd > tool_polyp_thickness(&t->polyp[i])) {
		*which = release(t);
		ev |= TOOL_EVENT_RELEASE;
	}
	i = t->captured;
	t->loop_m = i >= 0 ? fmax(cmd, tool_polyp_thickness(&t->polyp[i])) :
			     cmd;
	place_loop(t);
	i = meet(t, par, closing);
	if (i >= 0) {
		*which = i;
		ev |= TOOL_EVENT_CAPTURE;
		t->loop_m = fmax(cmd, tool_polyp_thickness(&t->polyp[i]));
	}
	if (t->captured >= 0) {
		*which = t->captured;
		ev |= cut(t, par, pedal, dt_s);
		t->loop_m = t->captured >= 0 ? t->loop_m : cmd;
	}
	place_loop(t);
	if (pedal && t->captured < 0 && !t->injured && in->wall &&
	    t->depth_m > 0 && loop_on_wall(t, par, in)) {
		t->injured = true;
		vec3_copy(t->injury_at, in->wall_point);
		ev |= TOOL_EVENT_INJURY;
	}
	return ev;
}

/* The needle's point in polyp P's wall under its base. */
static bool under_base(const struct tool *t, const struct tool_params *par,
		       const struct tool_polyp *p)
{
	double x[3], depth, r = p->size_m / 2 + par->margin_m;

	vec3_sub(x, t->needle, p->base);
	depth = -vec3_dot(x, p->normal);
	vec3_axpy(x, x, depth, p->normal);
	return depth >= 0 && depth <= par->needle_m && vec3_dot(x, x) <= r * r;
}

/* The needle's step after the pose: out, it injects under the first
 * sessile or flat base it is in; *WHICH the polyp it lifted. */
static unsigned needle_step(struct tool *t, const struct tool_params *par,
			    double dt_s, int *which)
{
	bool out = t->depth_m > 0 && t->opening > 0.5;

	vec3_axpy(t->needle, t->pose.tip, out ? par->needle_m : 0,
		  t->pose.dir);
	for (int i = 0; out && i < t->polyps; i++) {
		struct tool_polyp *p = &t->polyp[i];

		if (p->paris == ANATOMY_PARIS_IP ||
		    p->state != TOOL_POLYP_IN_PLACE || !under_base(t, par, p)) {
			continue;
		}
		p->injected_m3 += par->inject_m3_per_s * dt_s;
		if (!p->lifted && p->injected_m3 >= par->lift_m3) {
			p->lifted = true;
			*which = i;
			return TOOL_EVENT_LIFT;
		}
		return 0;
	}
	return 0;
}

/* The jaws close: the handle, opened past one half since they last
 * closed, closed now, the tool out of the channel. */
static bool jaws_close(struct tool *t, const struct tool_params *par)
{
	t->armed |= t->opening > 0.5;
	if (!t->armed || t->opening > par->closed_opening || t->depth_m <= 0) {
		return false;
	}
	t->armed = false;
	return true;
}

/* Point X within REACH_M of the caller's wall. */
static bool near_wall(const double x[3], const struct tool_input *in,
		      double reach_m)
{
	double d[3];

	vec3_sub(d, x, in->wall_point);
	return in->wall && vec3_dot(d, in->wall_normal) <= reach_m;
}

/* The polyp in place whose body the forceps' cups reach, or -1. */
static int bitten(const struct tool *t, const struct tool_params *par)
{
	for (int i = 0; i < t->polyps; i++) {
		const struct tool_polyp *p = &t->polyp[i];
		double c[3], h = tool_polyp_height(p, par->lift_m);

		vec3_axpy(c, p->base, h / 2, p->normal);
		if (p->state == TOOL_POLYP_IN_PLACE &&
		    vec3_dist(c, t->jaws) <= p->size_m / 2 + par->jaw_m) {
			return i;
		}
	}
	return -1;
}

/* The forceps' step after the pose; *WHICH the polyp bitten. */
static unsigned forceps_step(struct tool *t, const struct tool_params *par,
			     const struct tool_input *in, int *which)
{
	int i;

	vec3_axpy(t->jaws, t->pose.tip, par->jaw_m, t->pose.dir);
	if (!jaws_close(t, par)) {
		return 0;
	}
	i = bitten(t, par);
	if (i < 0 && !near_wall(t->jaws, in, par->jaw_m)) {
		return 0;
	}
	vec3_copy(t->bite_at, t->jaws);
	*which = i;
	if (i < 0) {
		return TOOL_EVENT_BITE;
	}
	t->polyp[i].bites++;
	if (t->polyp[i].size_m <= par->forceps_max_m) {
		t->polyp[i].state = TOOL_POLYP_RETRIEVED; /* in the cups */
		return TOOL_EVENT_BITE | TOOL_EVENT_CUT | TOOL_EVENT_RETRIEVE;
	}
	return TOOL_EVENT_BITE;
}

/* The clip's step after the pose: placed, it closes the first bleeding
 * point within half its jaws' length; *WHICH that polyp. */
static unsigned clip_step(struct tool *t, const struct tool_params *par,
			  const struct tool_input *in, int *which)
{
	vec3_axpy(t->jaws, t->pose.tip, par->clip_m, t->pose.dir);
	if (!jaws_close(t, par) || !near_wall(t->jaws, in, par->clip_m)) {
		return 0;
	}
	vec3_copy(t->clip_at, t->jaws);
	t->clips++;
	for (int i = 0; i < t->polyps; i++) {
		struct tool_polyp *p = &t->polyp[i];

		if (p->bleed == TOOL_BLEED_BLEEDING &&
		    vec3_dist(p->base, t->clip_at) <= par->clip_m / 2) {
			p->bleed = TOOL_BLEED_CLIPPED;
			p->bleed_m3_s = 0;
			*which = i;
			return TOOL_EVENT_CLIP | TOOL_EVENT_CLIPPED;
		}
	}
	return TOOL_EVENT_CLIP;
}

/* Every bleeding point sheds its step's blood (its flow, after the step,
 * says whether it did); one that has bled bleed_stop_s stops by itself
 * instead when FREE (no other polyp's event this step). */
static unsigned bleed_step(struct tool *t, const struct tool_params *par,
			   double dt_s, bool free, int *which)
{
	unsigned ev = 0;

	for (int i = 0; i < t->polyps; i++) {
		struct tool_polyp *p = &t->polyp[i];
		double shed = p->bleed_m3_s * dt_s;

		if (p->bleed != TOOL_BLEED_BLEEDING) {
			continue;
		}
		if (free && p->bleed_s >= par->bleed_stop_s - dt_s / 2) {
			p->bleed = TOOL_BLEED_STOPPED;
			p->bleed_m3_s = 0;
			*which = i;
			ev = TOOL_EVENT_STOPPED;
			free = false;
			continue;
		}
		p->blood_m3 += shed;
		t->blood_m3 += shed;
		p->bleed_s += dt_s;
	}
	return ev;
}

/* The suction takes the first small cut polyp the channel's exit
 * reaches; *WHICH it. */
static unsigned retrieve_step(struct tool *t, const struct tool_params *par,
			      const struct tool_input *in, int *which)
{
	for (int i = 0; in->suction && i < t->polyps; i++) {
		struct tool_polyp *p = &t->polyp[i];

		if (p->state != TOOL_POLYP_CUT ||
		    p->size_m > par->retrieve_max_m) {
			continue;
		}
		if (vec3_dist(p->at, t->pose.exit) <=
		    p->size_m / 2 + par->retrieve_reach_m) {
			p->state = TOOL_POLYP_RETRIEVED;
			*which = i;
			return TOOL_EVENT_RETRIEVE;
		}
	}
	return 0;
}

/* -------------------------------------------------------------- the fall */

/* A ring's wall against gravity: the lumen's (colon C's ring) in the
 * frame Q of its centreline point, gravity's direction DOWN. */
struct wall {
	const struct colon *c;
	struct colon_ring ring;
	double gu, gv; /* DOWN along the frame's u and v */
};

/* How far the wall at THETA lies along DOWN from the centreline:
 * r(theta) (cos theta u + sin theta v) . down. */
static double depth_at(const struct wall *w, double theta)
{
	return colon_ring_radius(w->c, &w->ring, theta) *
	       (cos(theta) * w->gu + sin(theta) * w->gv);
}

/* The lowest of the points seen so far round a ring, and the next. */
struct lowest {
	double th, f;
};

static double seen(struct lowest *lo, const struct wall *w, double th)
{
	double f = depth_at(w, th);

	if (f > lo->f) {
		lo->f = f;
		lo->th = th;
	}
	return f;
}

/* The angle round W's ring where its wall lies lowest: of
 * TOOL_REST_COARSE points from gravity's own (exactly it in a round
 * lumen), then of golden sections between the best one's neighbours,
 * the lowest seen. */
static double lowest(const struct wall *w)
{
	const double step = 2 * M_PI / TOOL_REST_COARSE, k = 0.5 * (sqrt(5) - 1);
	struct lowest lo = { .th = atan2(w->gv, w->gu), .f = -INFINITY };
	double th = lo.th, a, b, x1, x2, f1, f2;

	for (int i = 0; i < TOOL_REST_COARSE; i++) {
		seen(&lo, w, th + i * step);
	}
	a = lo.th - step;
	b = lo.th + step;
	x1 = b - k * (b - a);
	x2 = a + k * (b - a);
	f1 = seen(&lo, w, x1);
	f2 = seen(&lo, w, x2);
	for (int i = 2; i < TOOL_REST_FINE; i++) {
		if (f1 >= f2) {
			b = x2;
			x2 = x1;
			f2 = f1;
			x1 = b - k * (b - a);
			f1 = seen(&lo, w, x1);
		} else {
			a = x1;
			x1 = x2;
			f1 = f2;
			x2 = a + k * (b - a);
			f2 = seen(&lo, w, x2);
		}
	}
	return lo.th;
}

/* Cut polyp P's rest in colon C under gravity's direction DOWN: the
 * lowest wall point of its ring, its body's radius in (the undeformed
 * wall's, the ring's radius out to it kept for the gas to scale); it
 * falls there. */
static void find_rest(const struct colon *c, struct tool_polyp *p,
		      const double down[3])
{
	struct centreline_point q;
	struct wall w = { .c = c };
	double out[3], th, r;

	centreline_at_s(colon_centreline(c), p->s_m, &q);
	colon_ring_at(c, p->s_m, &w.ring);
	w.gu = vec3_dot(q.u, down);
	w.gv = vec3_dot(q.v, down);
	th = lowest(&w);
	vec3_scale(out, q.u, cos(th));
	vec3_axpy(out, out, sin(th), q.v);
	r = colon_ring_radius(c, &w.ring, th);
	vec3_axpy(p->rest, q.p, r - p->size_m / 2, out);
	vec3_scale(p->rest_wall, out, r);
	p->rest_ok = true;
	p->lies = false;
}

/* P a step DT_S nearer TO, pulled by G_M_S2 against the drag of TAU_S,
 * exactly for a constant pull; true if it moved. */
static bool fall_step(struct tool_polyp *p, const double to[3],
		      double g_m_s2, double tau_s, double dt_s)
{
	double d[3], l, e = exp(-dt_s / tau_s), vt = g_m_s2 * tau_s, go;

	vec3_sub(d, to, p->at);
	l = vec3_norm(d);
	if (!(l > 0)) {
		p->fall_v = 0;
		return false;
	}
	go = vt * dt_s + (p->fall_v - vt) * tau_s * (1 - e);
	p->fall_v = vt + (p->fall_v - vt) * e;
	if (go >= l) {
		vec3_copy(p->at, to);
		p->fall_v = 0;
	} else {
		vec3_axpy(p->at, p->at, go / l, d);
	}
	return true;
}

/* The rests for gravity's direction DOWN: all sought again when it
 * turned; one found this step, the next due after the last found. */
static void seek_rest(struct tool *t, const struct colon *c,
		      const double down[3])
{
	int n = t->polyps;

	if (memcmp(down, t->down, sizeof(t->down))) {
		vec3_copy(t->down, down);
		for (int i = 0; i < n; i++) {
			t->polyp[i].rest_ok = false;
		}
	}
	for (int k = 0; k < n; k++) {
		int i = (t->next_rest + k) % n;
		struct tool_polyp *p = &t->polyp[i];

		if (p->state == TOOL_POLYP_CUT && !p->rest_ok) {
			find_rest(c, p, down);
			t->next_rest = (i + 1) % n;
			return;
		}
	}
}

/* The cut polyp published this step (tool.h): the next that moved since
 * it was, else the next lying; -1 none. */
static void tell(struct tool *t)
{
	int n = t->polyps, from = t->lying + 1, pick = -1;

	for (int pass = 0; pass < 2 && pick < 0; pass++) {
		for (int k = 0; k < n && pick < 0; k++) {
			const struct tool_polyp *p = &t->polyp[(from + k) % n];

			if (p->state == TOOL_POLYP_CUT && (pass || p->moved)) {
				pick = (from + k) % n;
			}
		}
	}
	t->lying = pick;
	if (pick >= 0) {
		t->polyp[pick].moved = false;
	}
}

/*
 * Cut polyp P a step on with the gas's radius factor F at its place: its
 * rest where the gas holds the wall (moved along the ring's radius by
 * (F - 1) times it: exactly the rest at F 1); lying there, carried with
 * the wall; else a step of its fall towards it (G_M_S2, TAU_S, DT_S:
 * fall_step()), lying once there. True if it moved.
 */
static bool settle(struct tool_polyp *p, double f, double g_m_s2,
		   double tau_s, double dt_s)
{
	double to[3];
	bool moved;

	vec3_axpy(to, p->rest, f - 1, p->rest_wall);
	if (p->lies) {
		moved = memcmp(to, p->at, sizeof(to)) != 0;
		vec3_copy(p->at, to);
		return moved;
	}
	moved = fall_step(p, to, g_m_s2, tau_s, dt_s);
	p->lies = p->rest_ok && memcmp(to, p->at, sizeof(to)) == 0;
	return moved;
}

void tool_fall(struct tool *t, const struct tool_params *par,
	       const struct colon *c, const double g[3],
	       const double *factor, double dt_s)
{
	double a = vec3_norm(g), down[3];

	if (a > 0 && isfinite(a) && c && colon_anatomy(c) && t->polyps > 0) {
		vec3_scale(down, g, 1 / a);
		seek_rest(t, c, down);
		for (int i = 0; i < t->polyps; i++) {
			struct tool_polyp *p = &t->polyp[i];

			if (p->state != TOOL_POLYP_CUT) {
				continue;
			}
			if (settle(p, factor ? gas_factor_at(c, factor, p->s_m)
					     : 1,
				   a, par->fall_drag_s, dt_s)) {
				p->moved = true;
			}
		}
	}
	tell(t);
}

int tool_polyp_fate(const struct tool_polyp *p, const struct tool_params *par)
{
	if (p->state == TOOL_POLYP_IN_PLACE && p->bites > 0 &&
	    p->size_m > par->forceps_max_m) {
		return TOOL_FATE_PARTLY;
	}
	return p->state;
}

/* IN is a stale reading: the tool holds still, the pedal up. */
static bool input_still(const struct tool_input *in)
{
	return !isfinite(in->depth_m) || !isfinite(in->opening);
}

double tool_input_depth(const struct tool *t, const struct tool_input *in)
{
	return input_still(in) ? t->depth_m : in->depth_m;
}

unsigned tool_step(struct tool *t, const struct tool_params *par,
		   const struct endosim_scope_state *sc,
		   const struct tool_input *in, double dt_s, int *polyp)
{
	bool still = input_still(in);
	bool pedal = in->pedal && !still;
	unsigned ev = 0;
	int which = -1;

	if (!still) {
		t->depth_m = in->depth_m;
		t->opening = clamp01(in->opening);
	}
	t->pedal = pedal;
	if (!pedal) {
		t->injured = false;
	}
	tool_pose(par, sc, t->depth_m, &t->pose);
	if (t->kind == TOOL_SNARE) {
		ev = snare_step(t, par, in, pedal, dt_s, &which);
	} else if (t->kind == TOOL_NEEDLE) {
		ev = needle_step(t, par, dt_s, &which);
	} else if (t->kind == TOOL_FORCEPS) {
		ev = forceps_step(t, par, in, &which);
	} else if (t->kind == TOOL_CLIP) {
		ev = clip_step(t, par, in, &which);
	}
	ev |= bleed_step(t, par, dt_s, !ev || which < 0, &which);
	if (!ev || which < 0) {
		ev |= retrieve_step(t, par, in, &which);
	}
	if (polyp) {
		*polyp = which;
	}
	return ev;
}

void tool_publish(const struct tool *t, unsigned events, int polyp,
		  struct endosim_tool_state *out)
{
	double most = 0;

	memset(out, 0, sizeof(*out));
	out->kind = (uint32_t)t->kind;
	out->pedal = t->pedal;
	out->snare_m = t->snare_m;
	out->depth_m = t->depth_m;
	out->opening = t->opening;
	out->loop_m = t->kind == TOOL_SNARE ? t->loop_m : 0;
	vec3_copy(out->tip, t->pose.tip);
	vec3_copy(out->loop_centre, t->loop_centre);
	out->captured = t->captured;
	out->events = events;
	out->event_polyp = polyp;
	out->clips = (uint32_t)t->clips;
	out->polyps = (uint32_t)t->polyps;
	out->blood_m3 = t->blood_m3;
	vec3_copy(out->clip_at, t->clip_at);
	out->lying_polyp = t->lying;
	if (t->lying >= 0 && t->lying < t->polyps) {
		vec3_copy(out->lying_at, t->polyp[t->lying].at);
	}
	for (int i = 0; i < t->polyps; i++) {
		const struct tool_polyp *p = &t->polyp[i];

		out->polyp[i] = (struct endosim_tool_polyp){
			.state = (uint32_t)p->state, .lifted = p->lifted,
			.energy_j = p->energy_j, .bites = (uint32_t)p->bites,
			.bleed = (uint32_t)p->bleed,
			.bleed_m3_s = p->bleed_m3_s, .blood_m3 = p->blood_m3,
		};
		vec3_copy(out->polyp[i].at, p->at);
		if (p->bleed_m3_s > most) {
			most = p->bleed_m3_s;
			vec3_copy(out->bleed_at, p->base);
		}
		out->bleeding += p->bleed_m3_s > 0;
		out->bleed_m3_s += p->bleed_m3_s;
	}
}
