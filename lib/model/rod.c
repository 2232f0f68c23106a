/* rod.c - see rod.h. */
#include "model/rod.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "model/rod_algebra.h"

#define HARD_COMPLIANCE 1e-10 /* m/N: a hard row's floor (0.1 nm per N)
				 keeps the system definite when rows are
				 redundant (both ends clamped) */

typedef double mat3[3][3];
typedef double mat6[6][6];

struct seg {
	double p[3], q[4], v[3], w[3]; /* centre, orientation, velocities */
	double p0[3], q0[4];           /* at the step's start */
	mat3 rm;                       /* R(q) now: d1, d2, d3 in columns */
	double dp[3], dth[3];          /* moved since the step's start (by
					  predict(), refresh()), or by
					  apply() */
	mat3 pinv, qinv;               /* effective inverse mass: translation,
					  rotation (world) */
	bool loaded;
};

/*
 * One side of a link: d C / d (dp, dtheta) of its segment in blocks,
 *   J = [ T  X ]   (position rows)
 *       [ 0  Z ]   (rotation rows)
 * and what the solve keeps of M^-1 J^T: P T^T, Q X^T, Q Z^T.
 */
struct side {
	int seg;           /* -1: the anchor (no motion) */
	double ts;         /* T = ts I (a joint: +-1), or 0: T as given */
	mat3 t, x, z;
	mat3 pt, qx, qz;
};

/* A row block: a joint between segments, or an anchor at an end. */
struct link {
	struct side s[2];  /* a (base side), b (tip side) */
	double alpha[6];   /* compliance per row */
	double tau[6];     /* damping time per row, s */
	double rest[3];    /* joints: theta0 */
	double c[6];       /* constraint now */
	mat6 l;            /* the Cholesky factor of the eliminated block */
	mat6 v;            /* L^-1 B, B the block to the next link */
	double d[6];       /* the compliance on the diagonal */
	double g[6];       /* right-hand side, then dlambda */
	double lambda[6];  /* accumulated multipliers this step */
	const struct rod_anchor *anchor; /* anchors: the frame */
};

struct rod {
	struct rod_params par;
	int n;             /* segments */
	double l;          /* segment length */
	double mass;       /* per segment */
	double inertia[3]; /* about d1, d2, d3 */
	struct seg *seg;
	struct rod_load *load;
	struct link *joint;        /* n - 1 */
	struct rod_anchor anchor[2];
	double anchor_moved[2][6];  /* the anchor's move this step: its
				       point (world), its turn (world) */
	bool held[2];
	struct link end[2];        /* the anchors' rows */
	struct link **chain;       /* the links in order, base to tip */
	int links;
	double h;                  /* the last step */
};

/* ---------------------------------------------------------------- life */

int rod_params_check(const struct rod_params *p, char *err, size_t errsize)
{
	const char *what = NULL;

	if (p->segments < ROD_MIN_SEGMENTS || p->segments > ROD_MAX_SEGMENTS) {
		what = "segments out of range";
	} else if (!(p->length_m > 0 && p->length_m < 100)) {
		what = "length_m must be positive";
	} else if (!(p->radius_m > 0 && p->radius_m < p->length_m)) {
		what = "radius_m must be positive and below the length";
	} else if (!(p->mass_per_m_kg > 0 && p->mass_per_m_kg < 1e3)) {
		what = "mass_per_m_kg must be positive";
	} else if (!(p->bending_n_m2 > 0 && p->bending_n_m2 < 1e6) ||
		   !(p->torsion_n_m2 > 0 && p->torsion_n_m2 < 1e6)) {
		what = "bending_n_m2 and torsion_n_m2 must be positive";
	} else if (!(p->damping_s >= 0 && p->damping_s <= 1) ||
		   !(p->drag_n_s_per_m2 >= 0 && p->drag_n_s_per_m2 < 1e6)) {
		what = "damping_s (0..1) or drag_n_s_per_m2 out of range";
	} else if (p->iterations < 1 || p->iterations > 8) {
		what = "iterations must be 1..8";
	}
	if (what) {
		snprintf(err, errsize, "rod: %s", what);
		return -EINVAL;
	}
	return 0;
}

static void set_joint_rows(struct rod *r, struct link *k, double ei,
			   double gj)
{
	double tau = r->par.damping_s;

	for (int i = 0; i < 3; i++) {
		k->alpha[i] = HARD_COMPLIANCE;
		k->tau[i] = 0;
		k->tau[3 + i] = tau;
	}
	k->alpha[3] = r->l / ei;
	k->alpha[4] = r->l / ei;
	k->alpha[5] = r->l / gj;
}

struct rod *rod_create(const struct rod_params *p)
{
	char err[128];
	struct rod *r;
	int n = p->segments;

	if (rod_params_check(p, err, sizeof(err))) {
		return NULL;
	}
	r = calloc(1, sizeof(*r));
	if (!r) {
		return NULL;
	}
	r->par = *p;
	r->n = n;
	r->l = p->length_m / n;
	r->mass = p->mass_per_m_kg * r->l;
	r->inertia[0] = r->mass * (3 * p->radius_m * p->radius_m +
				   r->l * r->l) / 12;
	r->inertia[1] = r->inertia[0];
	r->inertia[2] = r->mass * p->radius_m * p->radius_m / 2;
	r->seg = calloc((size_t)n, sizeof(*r->seg));
	r->load = calloc((size_t)n, sizeof(*r->load));
	r->joint = calloc((size_t)n - 1, sizeof(*r->joint));
	r->chain = calloc((size_t)n + 1, sizeof(*r->chain));
	if (!r->seg || !r->load || !r->joint || !r->chain) {
		rod_destroy(r);
		return NULL;
	}
	for (int j = 0; j < n - 1; j++) {
		r->joint[j].s[0].seg = j;
		r->joint[j].s[1].seg = j + 1;
		set_joint_rows(r, &r->joint[j], p->bending_n_m2,
			       p->torsion_n_m2);
	}
	r->end[ROD_BASE].s[0].seg = -1;
	r->end[ROD_BASE].s[1].seg = 0;
	r->end[ROD_TIP].s[0].seg = n - 1;
	r->end[ROD_TIP].s[1].seg = -1;
	for (int i = 0; i < n; i++) {
		vec3_set(r->seg[i].p, 0, 0, (i + 0.5) * r->l);
		r->seg[i].q[0] = 1;
		rod_algebra_m3_identity(r->seg[i].rm, 1);
	}
	return r;
}

void rod_destroy(struct rod *r)
{
	if (!r) {
		return;
	}
	free(r->seg);
	free(r->load);
	free(r->joint);
	free(r->chain);
	free(r);
}

int rod_segments(const struct rod *r)
{
	return r->n;
}

double rod_segment_length(const struct rod *r)
{
	return r->l;
}

const struct rod_params *rod_params(const struct rod *r)
{
	return &r->par;
}

/* A unit vector normal to unit T, near D (or any when D is along T). */
static void normal_to(const double t[3], const double d[3], double out[3])
{
	double guess[3];

	vec3_axpy(out, d, -vec3_dot(d, t), t);
	if (vec3_normalize(out) > 1e-9) {
		return;
	}
	vec3_set(guess, fabs(t[0]) < 0.9 ? 1 : 0, fabs(t[0]) < 0.9 ? 0 : 1, 0);
	vec3_axpy(out, guess, -vec3_dot(guess, t), t);
	vec3_normalize(out);
}

/* U carried from tangent A to tangent B by the rotation about A x B
 * (Rodrigues). */
static void transport(const double a[3], const double b[3], double u[3])
{
	double k[3], ku[3], c = vec3_dot(a, b), sn, ka;

	vec3_cross(k, a, b);
	sn = vec3_normalize(k);
	if (sn < 1e-12) {
		return;
	}
	ka = vec3_dot(k, u);
	vec3_cross(ku, k, u);
	vec3_scale(u, u, c);
	vec3_axpy(u, u, sn, ku);
	vec3_axpy(u, u, ka * (1 - c), k);
}

void rod_frame_quat(const double t[3], const double u[3], double q[4])
{
	double d1[3], d2[3], m[3][3];

	normal_to(t, u, d1);
	vec3_cross(d2, t, d1);
	for (int k = 0; k < 3; k++) {
		m[k][0] = d1[k];
		m[k][1] = d2[k];
		m[k][2] = t[k];
	}
	rod_algebra_quat_from_matrix(m, q);
}

void rod_lay(struct rod *r, const double (*ends)[3], const double d1[3])
{
	double u[3], t_prev[3] = { 0, 0, 0 };

	for (int i = 0; i < r->n; i++) {
		struct seg *s = &r->seg[i];
		double t[3];

		vec3_sub(t, ends[i + 1], ends[i]);
		vec3_normalize(t);
		if (i == 0) {
			vec3_copy(u, d1);
		} else {
			transport(t_prev, t, u);
		}
		rod_frame_quat(t, u, s->q);
		rod_algebra_quat_axis_d1(s->q, u);
		rod_algebra_quat_matrix(s->q, s->rm);
		vec3_add(s->p, ends[i], ends[i + 1]);
		vec3_scale(s->p, s->p, 0.5);
		vec3_set(s->v, 0, 0, 0);
		vec3_set(s->w, 0, 0, 0);
		vec3_copy(t_prev, t);
	}
	rod_clear_loads(r);
}

void rod_set_rest(struct rod *r, int joint, const double theta0[3])
{
	vec3_copy(r->joint[joint].rest, theta0);
}

void rod_set_stiffness(struct rod *r, int joint, double ei_n_m2,
		       double gj_n_m2)
{
	set_joint_rows(r, &r->joint[joint], ei_n_m2, gj_n_m2);
}

void rod_rest_for_angle(double angle_rad, const double axis[3],
			double theta0[3])
{
	vec3_scale(theta0, axis, 2 * sin(angle_rad / 2));
}

void rod_clamp_compliance(const struct rod *r, double compliance[6])
{
	for (int i = 0; i < 3; i++) {
		compliance[i] = 0;
	}
	compliance[3] = r->l / (2 * r->par.bending_n_m2);
	compliance[4] = compliance[3];
	compliance[5] = r->l / (2 * r->par.torsion_n_m2);
}

void rod_set_anchor(struct rod *r, enum rod_end end,
		    const struct rod_anchor *a)
{
	struct link *k = &r->end[end];
	struct rod_anchor *an = &r->anchor[end];
	double *moved = r->anchor_moved[end];
	bool was = r->held[end];

	r->held[end] = a != NULL;
	memset(moved, 0, sizeof(r->anchor_moved[end]));
	if (!a) {
		return;
	}
	if (was) {
		double q[4];

		memcpy(q, a->q, sizeof(q));
		rod_algebra_quat_normalize(q);
		vec3_sub(moved, a->p, an->p);
		rod_algebra_rotation_since(q, an->q, moved + 3);
	}
	*an = *a;
	rod_algebra_quat_normalize(an->q);
	k->anchor = an;
	for (int i = 0; i < 6; i++) {
		k->alpha[i] = fmax(a->compliance[i], HARD_COMPLIANCE);
		k->tau[i] = fmax(a->damping_s[i], 0);
	}
}

void rod_clear_loads(struct rod *r)
{
	for (int i = 0; i < r->n; i++) {
		if (r->seg[i].loaded) {
			memset(&r->load[i], 0, sizeof(r->load[i]));
			r->seg[i].loaded = false;
		}
	}
}

struct rod_load *rod_load(struct rod *r, int i)
{
	r->seg[i].loaded = true;
	return &r->load[i];
}

void rod_load_point(struct rod_load *l, const double off[3],
		    const double f[3], const double k[3][3],
		    const double b[3][3], const double v_ref[3])
{
	mat3 e, me;

	/* the point moves by dp - [off]x dtheta: a spring K there has the
	 * rotational block [off]x^T K [off]x = -[off]x K [off]x */
	rod_algebra_m3_cross(e, off, 1);
	if (f) {
		double t[3];

		vec3_add(l->f, l->f, f);
		vec3_cross(t, off, f);
		vec3_add(l->tau, l->tau, t);
	}
	for (int pass = 0; pass < 2; pass++) {
		const double (*m)[3] = pass ? b : k;
		double (*lt)[3] = pass ? l->bt : l->kt;
		double (*lr)[3] = pass ? l->br : l->kr;

		if (!m) {
			continue;
		}
		memset(me, 0, sizeof(me));
		for (int i = 0; i < 3; i++) {
			for (int j = 0; j < 3; j++) {
				lt[i][j] += m[i][j];
				for (int c = 0; c < 3; c++) {
					me[i][j] += m[i][c] * e[c][j];
				}
			}
		}
		for (int i = 0; i < 3; i++) {
			for (int j = 0; j < 3; j++) {
				lr[i][j] -= e[i][0] * me[0][j] +
					    e[i][1] * me[1][j] +
					    e[i][2] * me[2][j];
			}
		}
	}
	if (b && v_ref) {
		double bv[3] = { 0, 0, 0 }, t[3];

		rod_algebra_m3_mv_acc(b, v_ref, 1, bv);
		vec3_add(l->btv, l->btv, bv);
		vec3_cross(t, off, bv);
		vec3_add(l->brw, l->brw, t);
	}
}

/* ---------------------------------------------------------------- step */

/*
 * Segment I's effective masses M + h B + h^2 K (translation, rotation),
 * inverted, its matrix R(q) at the step's start, and its predicted motion
 * over the step, dp = h v*, dtheta = h w* with (M + hB + h^2K) v* = M v +
 * h (f + B v_ref), which the step's first iteration takes in linearly.
 * Returns -1 when a mass is not definite (bad loads).
 */
static int predict(struct rod *r, int i, double h)
{
	struct seg *s = &r->seg[i];
	const struct rod_load *ld = &r->load[i];
	double vs[3], ws[3], drag = r->par.drag_n_s_per_m2 * r->l;
	const double (*rm)[3] = (const double(*)[3])s->rm;
	mat3 mt, mr;

	rod_algebra_quat_matrix(s->q, s->rm);
	/* drag: towards rest */
	rod_algebra_m3_identity(mt, r->mass + h * drag);
	for (int a = 0; a < 3; a++) {
		for (int b = 0; b < 3; b++) {
			mr[a][b] = rm[a][0] * r->inertia[0] * rm[b][0] +
				   rm[a][1] * r->inertia[1] * rm[b][1] +
				   rm[a][2] * r->inertia[2] * rm[b][2];
		}
	}
	vec3_scale(vs, s->v, r->mass);
	vec3_set(ws, 0, 0, 0);
	rod_algebra_m3_mv_acc(mr, s->w, 1, ws);
	if (s->loaded) {
		for (int a = 0; a < 3; a++) {
			vs[a] += h * (ld->f[a] + ld->btv[a]);
			ws[a] += h * (ld->tau[a] + ld->brw[a]);
			for (int b = 0; b < 3; b++) {
				mt[a][b] += h * ld->bt[a][b] +
					    h * h * ld->kt[a][b];
				mr[a][b] += h * ld->br[a][b] +
					    h * h * ld->kr[a][b];
			}
		}
	}
	if (rod_algebra_m3_inverse(mt, s->pinv) ||
	    rod_algebra_m3_inverse(mr, s->qinv)) {
		return -1;
	}
	vec3_set(s->dp, 0, 0, 0);
	rod_algebra_m3_mv_acc(s->pinv, vs, h, s->dp);
	vec3_set(s->dth, 0, 0, 0);
	rod_algebra_m3_mv_acc(s->qinv, ws, h, s->dth);
	return 0;
}

/* The end point offset of segment S: (l/2) d3 at the tip side, minus at
 * the base side (its matrix as refresh() left it). */
static void end_offset(const struct rod *r, const struct seg *s,
		       enum rod_end side, double e[3])
{
	double h = side == ROD_TIP ? r->l / 2 : -r->l / 2;

	vec3_set(e, h * s->rm[0][2], h * s->rm[1][2], h * s->rm[2][2]);
}

/* Each segment's matrix and its motion since the step's start. */
static void refresh(struct rod *r)
{
	for (int i = 0; i < r->n; i++) {
		struct seg *s = &r->seg[i];

		rod_algebra_quat_matrix(s->q, s->rm);
		vec3_sub(s->dp, s->p, s->p0);
		rod_algebra_rotation_since(s->q, s->q0, s->dth);
	}
}

/*
 * A joint's rows: C = (end_a - end_b, 2 Im(conj(q_a) q_b) - theta0) and
 * its blocks: a [I, -[e_a]x; 0, -G], b [-I, [e_b]x; 0, G]
 * (rod_algebra_relative()).
 */
static void joint_rows(const struct rod *r, struct link *k)
{
	struct side *sa = &k->s[0], *sb = &k->s[1];
	const struct seg *a = &r->seg[sa->seg], *b = &r->seg[sb->seg];
	double ea[3], eb[3], pa[3], pb[3], q[4];

	end_offset(r, a, ROD_TIP, ea);
	end_offset(r, b, ROD_BASE, eb);
	vec3_add(pa, a->p, ea);
	vec3_add(pb, b->p, eb);
	rod_algebra_relative(a->q, b->q, (const double(*)[3])a->rm, q, sb->z);
	for (int i = 0; i < 3; i++) {
		k->c[i] = pa[i] - pb[i];
		k->c[3 + i] = 2 * q[1 + i] - k->rest[i];
		for (int j = 0; j < 3; j++) {
			sa->z[i][j] = -sb->z[i][j];
		}
	}
	sa->ts = 1;
	sb->ts = -1;
	rod_algebra_m3_cross(sa->x, ea, -1);
	rod_algebra_m3_cross(sb->x, eb, 1);
}

/* An anchor's rows: C = (R^T (end - P), 2 Im(conj(Q) q)), the segment's
 * blocks [R^T, -R^T [e]x; 0, G]. */
static void anchor_rows(const struct rod *r, struct link *k,
			enum rod_end end)
{
	const struct rod_anchor *an = k->anchor;
	struct side *sd = &k->s[end == ROD_BASE ? 1 : 0];
	const struct seg *s = &r->seg[sd->seg];
	double e[3], pe[3], d[3], q[4], ra[3][3];
	mat3 ex;

	end_offset(r, s, end, e);
	vec3_add(pe, s->p, e);
	vec3_sub(d, pe, an->p);
	rod_algebra_quat_matrix(an->q, ra);
	rod_algebra_relative(an->q, s->q, (const double(*)[3])ra, q, sd->z);
	rod_algebra_m3_cross(ex, e, -1);
	sd->ts = 0;
	for (int a = 0; a < 3; a++) {
		k->c[a] = ra[0][a] * d[0] + ra[1][a] * d[1] + ra[2][a] * d[2];
		k->c[3 + a] = 2 * q[1 + a];
		for (int c = 0; c < 3; c++) {
			sd->t[a][c] = ra[c][a];
			sd->x[a][c] = ra[0][a] * ex[0][c] + ra[1][a] * ex[1][c] +
				      ra[2][a] * ex[2][c];
		}
	}
}

static void rows(struct rod *r)
{
	for (int c = 0; c < r->links; c++) {
		struct link *k = r->chain[c];

		if (k == &r->end[ROD_BASE]) {
			anchor_rows(r, k, ROD_BASE);
		} else if (k == &r->end[ROD_TIP]) {
			anchor_rows(r, k, ROD_TIP);
		} else {
			joint_rows(r, k);
		}
	}
}

/*
 * Link K's right-hand side: (-C - alpha~ lambda - gamma J dx) / (1 +
 * gamma) per row, and its diagonal's compliance alpha~ / (1 + gamma)
 * (Macklin et al.'s damped XPBD, each row scaled to keep it symmetric).
 * FIRST: the rows were taken at the step's start and the segments' dx is
 * the predicted motion, not yet made: C is C + J dx there.
 */
static void rhs(const struct rod *r, struct link *k, double h, bool first)
{
	double jdx[6] = { 0 };

	for (int i = 0; i < 2; i++) {
		const struct side *sd = &k->s[i];
		const struct seg *sg;

		if (sd->seg < 0) {
			continue;
		}
		sg = &r->seg[sd->seg];
		if (sd->ts) {
			vec3_axpy(jdx, jdx, sd->ts, sg->dp);
		} else {
			rod_algebra_m3_mv_acc(sd->t, sg->dp, 1, jdx);
		}
		rod_algebra_m3_mv_acc(sd->x, sg->dth, 1, jdx);
		rod_algebra_m3_mv_acc(sd->z, sg->dth, 1, jdx + 3);
	}
	for (int i = 0; first && i < 6; i++) {
		k->c[i] += jdx[i];
	}
	if (k == &r->end[ROD_BASE] || k == &r->end[ROD_TIP]) {
		/* a coupling damps the motion relative to its anchor's */
		const double *am = r->anchor_moved[k == &r->end[ROD_TIP]];
		const struct side *sd = &k->s[k == &r->end[ROD_BASE] ? 1 : 0];

		rod_algebra_m3_mv_acc(sd->t, am, -1, jdx);
		rod_algebra_m3_mv_acc(sd->z, am + 3, -1, jdx + 3);
	}
	for (int i = 0; i < 6; i++) {
		double at = k->alpha[i] / (h * h), gam = k->tau[i] / h;

		k->g[i] = (-k->c[i] - at * k->lambda[i] - gam * jdx[i]) /
			  (1 + gam);
		k->d[i] = at / (1 + gam);
	}
}

/* The side's share of the system: P T^T, Q X^T, Q Z^T. */
static void side_products(const struct rod *r, struct side *sd)
{
	const struct seg *s = &r->seg[sd->seg];

	if (sd->ts) {
		for (int i = 0; i < 3; i++) {
			vec3_scale(sd->pt[i], s->pinv[i], sd->ts);
		}
	} else {
		rod_algebra_m3_abt(s->pinv, sd->t, sd->pt);
	}
	rod_algebra_m3_abt(s->qinv, sd->x, sd->qx);
	rod_algebra_m3_abt(s->qinv, sd->z, sd->qz);
}

/* OUT += J_1 M^-1 J_2^T for sides 1 and 2 of the same segment:
 * [T1 P T2^T + X1 Q X2^T, X1 Q Z2^T; Z1 Q X2^T, Z1 Q Z2^T]. */
static void coupling(const struct side *s1, const struct side *s2, mat6 out)
{
	if (s1->ts) {
		for (int i = 0; i < 3; i++) {
			for (int j = 0; j < 3; j++) {
				out[i][j] += s1->ts * s2->pt[i][j];
			}
		}
	} else {
		rod_algebra_m6_add_ab(out, 0, 0, s1->t, s2->pt);
	}
	rod_algebra_m6_add_ab(out, 0, 0, s1->x, s2->qx);
	rod_algebra_m6_add_ab(out, 0, 3, s1->x, s2->qz);
	rod_algebra_m6_add_ab(out, 3, 0, s1->z, s2->qx);
	rod_algebra_m6_add_ab(out, 3, 3, s1->z, s2->qz);
}

/*
 * Factors the chain's block-tridiagonal system: with S_c = L_c L_c^T,
 * S_c = A_cc - V_{c-1}^T V_{c-1} and V_c = L_c^-1 B_c, where A_cc = J M^-1
 * J^T + D and B_c = J_{c,b} M^-1 J_{c+1,a}^T through the segment links c
 * and c + 1 share. Returns -1 when not definite.
 */
static int factor(struct rod *r)
{
	for (int c = 0; c < r->links; c++) {
		for (int i = 0; i < 2; i++) {
			if (r->chain[c]->s[i].seg >= 0) {
				side_products(r, &r->chain[c]->s[i]);
			}
		}
	}
	for (int c = 0; c < r->links; c++) {
		struct link *k = r->chain[c];

		memset(k->l, 0, sizeof(k->l));
		for (int i = 0; i < 2; i++) {
			if (k->s[i].seg >= 0) {
				coupling(&k->s[i], &k->s[i], k->l);
			}
		}
		for (int i = 0; i < 6; i++) {
			k->l[i][i] += k->d[i];
		}
		if (c > 0) {
			const struct link *p = r->chain[c - 1];

			for (int i = 0; i < 6; i++) {
				for (int j = 0; j <= i; j++) {
					double t = 0;

					for (int m = 0; m < 6; m++) {
						t += p->v[m][i] * p->v[m][j];
					}
					k->l[i][j] -= t;
				}
			}
		}
		if (rod_algebra_chol6(k->l)) {
			return -1;
		}
		if (c + 1 == r->links) {
			break;
		}
		memset(k->v, 0, sizeof(k->v));
		coupling(&k->s[1], &r->chain[c + 1]->s[0], k->v);
		rod_algebra_lower_solve6(k->l, k->v);
	}
	return 0;
}

/* Solves the factored system for the links' g in place: dlambda. */
static void solve(struct rod *r)
{
	for (int c = 0; c < r->links; c++) {
		struct link *k = r->chain[c];

		if (c > 0) {
			const struct link *p = r->chain[c - 1];

			for (int i = 0; i < 6; i++) {
				double t = 0;

				for (int m = 0; m < 6; m++) {
					t += p->v[m][i] * p->g[m];
				}
				k->g[i] -= t;
			}
		}
		rod_algebra_lower_solve(k->l, k->g);
	}
	for (int c = r->links - 1; c >= 0; c--) {
		struct link *k = r->chain[c];

		if (c + 1 < r->links) {
			const double *x = r->chain[c + 1]->g;

			for (int i = 0; i < 6; i++) {
				double t = 0;

				for (int m = 0; m < 6; m++) {
					t += k->v[i][m] * x[m];
				}
				k->g[i] -= t;
			}
		}
		rod_algebra_upper_solve(k->l, k->g);
	}
}

/* Applies dlambda (in g): each segment moves by M^-1 J^T dlambda of the
 * links on both its sides, summed first (one turn per segment), and on
 * the FIRST iteration by its predicted motion too. */
static void apply(struct rod *r, bool first)
{
	for (int i = 0; i < r->n && !first; i++) {
		memset(r->seg[i].dp, 0, sizeof(r->seg[i].dp));
		memset(r->seg[i].dth, 0, sizeof(r->seg[i].dth));
	}
	for (int c = 0; c < r->links; c++) {
		struct link *k = r->chain[c];

		for (int i = 0; i < 6; i++) {
			k->lambda[i] += k->g[i];
		}
		for (int i = 0; i < 2; i++) {
			const struct side *sd = &k->s[i];
			struct seg *sg;

			if (sd->seg < 0) {
				continue;
			}
			sg = &r->seg[sd->seg];
			rod_algebra_m3_mv_acc(sd->pt, k->g, 1, sg->dp);
			rod_algebra_m3_mv_acc(sd->qx, k->g, 1, sg->dth);
			rod_algebra_m3_mv_acc(sd->qz, k->g + 3, 1, sg->dth);
		}
	}
	for (int i = 0; i < r->n; i++) {
		struct seg *sg = &r->seg[i];

		vec3_add(sg->p, sg->p, sg->dp);
		rod_algebra_quat_turn(sg->q, sg->dth);
	}
}

static void build_chain(struct rod *r)
{
	r->links = 0;
	if (r->held[ROD_BASE]) {
		r->chain[r->links++] = &r->end[ROD_BASE];
	}
	for (int j = 0; j < r->n - 1; j++) {
		r->chain[r->links++] = &r->joint[j];
	}
	if (r->held[ROD_TIP]) {
		r->chain[r->links++] = &r->end[ROD_TIP];
	}
	for (int c = 0; c < r->links; c++) {
		memset(r->chain[c]->lambda, 0, sizeof(r->chain[c]->lambda));
	}
}

/* Something could not be solved: NaN marks it for rod_finite(). */
static void broken(struct rod *r)
{
	r->seg[0].p[0] = NAN;
}

void rod_step(struct rod *r, double dt_s)
{
	double h = dt_s;

	r->h = h;
	build_chain(r);
	for (int i = 0; i < r->n; i++) {
		struct seg *s = &r->seg[i];

		if (predict(r, i, h)) {
			broken(r);
			return;
		}
		memcpy(s->p0, s->p, sizeof(s->p));
		memcpy(s->q0, s->q, sizeof(s->q));
	}
	/* the first iteration linearises at the step's start, where the
	 * segments are: the loads' predicted motion enters the solve
	 * linearly (rhs()), so that a rod at rest in equilibrium stays put
	 * whatever h and the inertia (rod.h) */
	for (int it = 0; it < r->par.iterations; it++) {
		if (it > 0) {
			refresh(r);
		}
		rows(r);
		for (int c = 0; c < r->links; c++) {
			rhs(r, r->chain[c], h, it == 0);
		}
		if (it == 0 && factor(r)) {
			broken(r);
			return;
		}
		solve(r);
		apply(r, it == 0);
	}
	refresh(r);
	for (int i = 0; i < r->n; i++) {
		struct seg *s = &r->seg[i];

		vec3_scale(s->v, s->dp, 1 / h);
		vec3_scale(s->w, s->dth, 1 / h);
	}
}

/* ---------------------------------------------------------------- results */

const double *rod_centre(const struct rod *r, int i)
{
	return r->seg[i].p;
}

const double *rod_quat(const struct rod *r, int i)
{
	return r->seg[i].q;
}

const double *rod_velocity(const struct rod *r, int i)
{
	return r->seg[i].v;
}

const double *rod_spin(const struct rod *r, int i)
{
	return r->seg[i].w;
}

void rod_frame(const struct rod *r, int i, double d1[3], double d2[3],
	       double d3[3])
{
	double m[3][3];

	rod_algebra_quat_matrix(r->seg[i].q, m);
	vec3_set(d1, m[0][0], m[1][0], m[2][0]);
	vec3_set(d2, m[0][1], m[1][1], m[2][1]);
	vec3_set(d3, m[0][2], m[1][2], m[2][2]);
}

void rod_end_point(const struct rod *r, int i, enum rod_end end,
		   double out[3])
{
	double e[3];

	end_offset(r, &r->seg[i], end, e);
	vec3_add(out, r->seg[i].p, e);
}

void rod_anchor_wrench(const struct rod *r, enum rod_end end, double f[3],
		       double tau[3])
{
	const struct link *k = &r->end[end];
	const struct side *sd = &k->s[end == ROD_BASE ? 1 : 0];
	double lam[6], pe[3], arm[3], t[3];

	vec3_set(f, 0, 0, 0);
	vec3_set(tau, 0, 0, 0);
	if (!r->held[end] || !(r->h > 0)) {
		return;
	}
	for (int a = 0; a < 6; a++) {
		lam[a] = k->lambda[a] / (r->h * r->h);
	}
	/* J^T lambda / h^2: the force T^T l_p, the torque about the centre
	 * X^T l_p + Z^T l_r; then about the end point */
	if (sd->ts) {
		vec3_scale(f, lam, sd->ts);
	} else {
		rod_algebra_m3_mtv_acc(sd->t, lam, f);
	}
	rod_algebra_m3_mtv_acc(sd->x, lam, tau);
	rod_algebra_m3_mtv_acc(sd->z, lam + 3, tau);
	rod_end_point(r, sd->seg, end, pe);
	vec3_sub(arm, r->seg[sd->seg].p, pe);
	vec3_cross(t, arm, f);
	vec3_add(tau, tau, t);
}

void rod_joint_rotation(const struct rod *r, int joint, double theta[3])
{
	double q[4], g[3][3], m[3][3];

	rod_algebra_quat_matrix(r->seg[joint].q, m);
	rod_algebra_relative(r->seg[joint].q, r->seg[joint + 1].q,
			     (const double(*)[3])m, q, g);
	vec3_set(theta, 2 * q[1], 2 * q[2], 2 * q[3]);
}

void rod_joint_moment(const struct rod *r, int joint, double m[3])
{
	const struct link *k = &r->joint[joint];
	double h2 = r->h > 0 ? r->h * r->h : 1;

	/* the row's force lambda / h^2 is -(d E / d theta): the moment that
	 * holds theta away from rest is its negative */
	vec3_set(m, -k->lambda[3] / h2, -k->lambda[4] / h2,
		 -k->lambda[5] / h2);
}

double rod_joint_gap(const struct rod *r)
{
	double most = 0;

	for (int j = 0; j + 1 < r->n; j++) {
		double a[3], b[3];

		rod_end_point(r, j, ROD_TIP, a);
		rod_end_point(r, j + 1, ROD_BASE, b);
		most = fmax(most, vec3_dist(a, b));
	}
	return most;
}

bool rod_finite(const struct rod *r)
{
	for (int i = 0; i < r->n; i++) {
		const struct seg *s = &r->seg[i];

		for (int a = 0; a < 3; a++) {
			if (!isfinite(s->p[a]) || !isfinite(s->v[a]) ||
			    !isfinite(s->w[a])) {
				return false;
			}
		}
		for (int a = 0; a < 4; a++) {
			if (!isfinite(s->q[a])) {
				return false;
			}
		}
	}
	return true;
}

double rod_kinetic_energy(const struct rod *r)
{
	double e = 0;

	for (int i = 0; i < r->n; i++) {
		const struct seg *s = &r->seg[i];
		double d[3][3];

		rod_frame(r, i, d[0], d[1], d[2]);
		e += r->mass * vec3_dot(s->v, s->v) / 2;
		for (int k = 0; k < 3; k++) {
			double w = vec3_dot(s->w, d[k]);

			e += r->inertia[k] * w * w / 2;
		}
	}
	return e;
}
