/*
 * centreline.h - the colon's centreline r(s): samples at a fixed step of
 * the material arc length s (m from the anal verge, measured on the
 * undeformed colon), each with a rotation-minimising frame and the
 * curvature, plus the integrated curvature (total turning angle) and the
 * arc length up to each sample.
 *
 * Frames: the double reflection method (Wang, Juettler, Zheng, Liu 2008,
 * "Computation of rotation minimizing frames"): (t, u, v) right-handed and
 * orthonormal, u and v carried along without twist about t.
 *
 * Integrated curvature: the paper's (Koerner and Maenner, section 5.2)
 *   K(i) = sum_{j=1..i} |r(j-1) - 2 r(j) + r(j+1)| / ds
 * which is the total turning angle of the curve up to sample i (rad).
 *
 * Mobile spans (the sigmoid and transverse colon, on their mesentery) can
 * bow: each sample strictly inside the span [s0, s1] moves by
 *   A sin^2(pi (s - s0) / (s1 - s0)) e
 * where A is the span's amplitude (m) and e a fixed unit direction across
 * the span (away from its chord, or the frame's u where the span is
 * straight). Position and tangent stay continuous at both ends (C1). Only
 * the span's own samples change; their frames are carried by double
 * reflection from the span's start and the small twist left at its end is
 * spread evenly over the span, so the frame stays continuous there too.
 * The turning angle and arc length of samples after the span shift by the
 * span's change, which is kept per span, not written into later samples.
 *
 * Allocation: centreline_create() and centreline_set_spans() allocate;
 * everything else does not, never blocks and is safe in the force loop.
 * One writer: centreline_bow() must not run while another thread reads
 * the same centreline.
 */
#ifndef ENDOSIM_CENTRELINE_H
#define ENDOSIM_CENTRELINE_H

#include <stddef.h>

#define CENTRELINE_MAX_SPANS 4
#define CENTRELINE_MIN_SAMPLES 8

struct centreline_point {
	double p[3]; /* position, m */
	double t[3]; /* unit tangent, towards the cecum */
	double u[3]; /* unit normal of the rotation-minimising frame */
	double v[3]; /* t x u */
	double k[3]; /* curvature vector d2r/ds2, 1/m (0 at both ends) */
};

struct centreline;

/*
 * A centreline through the N points PTS (m), which must be spaced STEP_M
 * apart along the curve (uniform in s: centreline_resample() makes them
 * so). U0, when not NULL, gives the direction of the first frame's u (it
 * is made normal to the first tangent); otherwise one is chosen. Returns
 * NULL with one line in ERR when N < CENTRELINE_MIN_SAMPLES, a point is
 * not finite, two points coincide, or memory runs out.
 */
struct centreline *centreline_create(const double (*pts)[3], size_t n,
				     double step_m, const double u0[3],
				     char *err, size_t errsize);

/* NULL is fine. */
void centreline_destroy(struct centreline *cl);

/*
 * Resamples the polyline PTS (N points, any spacing) at STEP_M along its
 * length, both ends kept: the step is shortened so that a whole number of
 * steps fits. Returns a malloc'd array of *OUT_N points and *OUT_STEP_M, or
 * NULL (ENOMEM, or EINVAL when the polyline is shorter than a few steps).
 */
double (*centreline_resample(const double (*pts)[3], size_t n, double step_m,
			     size_t *out_n, double *out_step_m))[3];

/*
 * Declares the mobile spans, COUNT ranges [s0, s1] in m (at most
 * CENTRELINE_MAX_SPANS, in order, each at least 8 steps long, at least two
 * steps clear of each other and of both ends). Resets every bow to 0.
 * Returns 0 or -EINVAL.
 */
int centreline_set_spans(struct centreline *cl, const double (*range)[2],
			 int count);

/* Bytes held by the centreline. */
size_t centreline_bytes(const struct centreline *cl);

/* Samples, step (m) and material length (m) of the whole centreline. */
size_t centreline_count(const struct centreline *cl);
double centreline_step(const struct centreline *cl);
double centreline_length(const struct centreline *cl);

/* Sample I (0 <= I < count), as deformed now. */
const struct centreline_point *centreline_sample(const struct centreline *cl,
						 size_t i);

/* Sample I before any bow. */
const struct centreline_point *centreline_base(const struct centreline *cl,
					       size_t i);

/* Total turning angle K(I), rad, and arc length up to sample I, m. */
double centreline_turning(const struct centreline *cl, size_t i);
double centreline_arclength(const struct centreline *cl, size_t i);

/* The deformed centreline's whole arc length, m. */
double centreline_total_arclength(const struct centreline *cl);

/*
 * The point at arc length LEN_M along the deformed centreline (clamped to
 * the centreline), interpolated between samples with its frame made
 * orthonormal again. Returns the material s (m) of that point. HINT, when
 * not NULL, is a sample index to start searching from and is updated (for
 * walks along the curve).
 */
double centreline_at_length(const struct centreline *cl, double len_m,
			    struct centreline_point *out, size_t *hint);

/* Only the position at arc length LEN_M (cheaper); HINT as above. */
void centreline_position_at_length(const struct centreline *cl, double len_m,
				   double out[3], size_t *hint);

/* The same at the material position S_M; returns the arc length there. */
double centreline_at_s(const struct centreline *cl, double s_m,
		       struct centreline_point *out);

/*
 * Bows mobile span SPAN by AMPLITUDE_M (any finite value; negative bows the
 * other way). Returns 0, or -EINVAL for a bad span or amplitude. Cost:
 * proportional to the span's samples, no allocation.
 */
int centreline_bow(struct centreline *cl, int span, double amplitude_m);

/*
 * Moves mobile span SPAN by a displacement given at COUNT nodes (m, any
 * direction): node k sits at the fraction (k + 1) / (COUNT + 1) of the
 * span, the span's ends stay put, and each sample between follows the
 * cubic Hermite curve through the knots with Catmull-Rom tangents inside
 * and none at the ends (position and tangent continuous, C1, where the
 * span meets the fixed colon). Frames, turning angle and arc length follow
 * as for a bow; the span's bow amplitude becomes 0. Returns 0, or -EINVAL
 * for a bad span, no node or a displacement that is not finite. Cost:
 * like centreline_bow(), no allocation.
 */
int centreline_displace(struct centreline *cl, int span,
			const double (*node)[3], int count);

/*
 * Where the fraction X (0..1) of a span with COUNT nodes falls: between
 * knots *J and *J + 1 (knot 0 and COUNT + 1 are the span's fixed ends,
 * knot k >= 1 node k - 1), with the linear weights W of both (a force
 * there is shared between them so).
 */
void centreline_knot_weights(double x, int count, int *j, double w[2]);

/* Spans declared; span SPAN's range (m) and amplitude (m). */
int centreline_spans(const struct centreline *cl);
void centreline_span_range(const struct centreline *cl, int span,
			   double *s0_m, double *s1_m);
double centreline_bow_amplitude(const struct centreline *cl, int span);

/* The span's bow direction e (unit). */
void centreline_bow_direction(const struct centreline *cl, int span,
			      double e[3]);

#endif
