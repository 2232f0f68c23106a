/*
 * flex.h - a colon that moves: its mobile segments (the sigmoid and the
 * transverse colon, `mobile = yes` in a case) on their mesentery, pushed
 * by the insertion tube.
 *
 * Each mobile span of the centreline (centreline.h) becomes a chain of
 * nodes, evenly spaced about node_spacing_m apart between its fixed ends
 * (node k at the fraction (k + 1) / (count + 1) of the span, as
 * centreline_displace() places them); a node's displacement y from rest
 * (m) obeys, every step,
 *   b dy/dt = F + m g - k_m (1 + (|y| / h)^2) y + k_c D2 y - k_b D4 y
 * across the course at rest (the mesentery holds the colon on its course:
 * a node moves in the plane normal to the course's tangent there, never
 * along it; a loop is the colon bulging, not stretching: each step's
 * displacement is projected on that plane, which balances the forces
 * exactly on a straight course and within a few per cent where the
 * course turns between nodes), m g the node's weight (mass_per_m_kg of
 * colon with its contents times the nodes' spacing, under the gravity
 * flex_set_gravity() gives: the transverse colon sags on its mesocolon),
 * F the forces the tube puts on the wall around it (flex_push(): shared
 * between the two knots around the contact by the knot weights, so that
 * action = reaction), k_m the mesentery's stiffness (the segment's
 * mesentery_n_per_m shared among its nodes: a uniform displacement of the
 * whole segment by y takes k_segment y), h the mesentery's height (the
 * case's mesentery_height_m: the mesentery stiffens as it stretches, 5x at
 * y = 2h), k_c the colon's own continuity (chain_n_per_m, D2 the second
 * difference along the chain: neighbours pull a pushed node's neighbours
 * along), k_b its wall's resistance to crumpling (bending_n_per_m, D4 the
 * fourth difference: a short ripple costs 16 k_b a node, a bulge as long as
 * the segment next to nothing; without it the tube hides its length in a
 * colon wrinkled between its nodes), b the tissue's damping (overdamped:
 * the colon has no inertia worth the name at these speeds). The span's ends
 * stay at rest (the fixed colon around it). Integrated implicitly (one
 * tridiagonal solve per span and coordinate; the stiffening taken at the
 * step's start, the tube's push easing as the wall yields with the
 * contacts' stiffness): stable at any step.
 *
 * The assistant's hand (flex_set_pad()): a pad pressed into the abdomen
 * compresses the abdominal wall and what lies under it onto the colon,
 * and the colon onto the retroperitoneum behind, so that within the
 * pad's reach (within radius_m of its axis, at any depth: the column of
 * the abdomen the hand squeezes) the mobile colon is held between the
 * hand and the back and cannot bulge in any direction as freely as
 * elsewhere: the assistant splints it on its course, pressing a loop's
 * apex back. So each node whose course at rest lies within the reach is
 * held towards its place at rest (the one its mesentery holds it to as
 * well), put back onto the pad's face along the press where that place
 * lies in front of it (the pad pushes the colon in), by a spring of
 * k_p = F / FLEX_PAD_GIVE_M (F the hand's force: soft tissue stiffens in
 * proportion to the stress it bears, Fung's exponential law, so the
 * harder the hand presses the stiffer the squeezed column), taken in the
 * step's implicit system like the mesentery (stable at any step). A loop
 * dragging a node out from under the hand leaves it held; a node whose
 * course lies elsewhere is not, wherever it goes. The grip's forces are
 * bounded by the hand's: their sum (the force the pad holds the colon
 * with: what the hand feels back, flex_pad_force()) is at most F, the
 * excess taken off every node held alike (the squeezed column shifts
 * under the hand as a whole; the forces that press the colon's parts
 * against each other cancel in the sum and stay), no node takes more
 * than F, and the chains holding a node are stepped again under the
 * forces so bounded: one more solve at most, fixed work.
 *
 * The centreline follows (centreline_displace()) whenever a node has moved
 * by more than FLEX_APPLY_M since it last did; the mesh follows where a
 * viewer places it (its vertices are offsets in their sample's frame), the
 * contact surface stays in the material placement (haptics.h).
 *
 * flex_create() allocates; the rest never allocates, blocks or prints: the
 * force loop attaches and steps it. One writer.
 */
#ifndef ENDOSIM_FLEX_H
#define ENDOSIM_FLEX_H

#include <stdbool.h>
#include <stddef.h>

#include "model/colon.h"
#include "proto/endosim_shm.h"

#define FLEX_MAX_NODES ENDOSIM_COLON_NODES /* all spans together */
#define FLEX_APPLY_M 1e-4   /* a node's move that re-lays the centreline */

struct flex_params {
	double node_spacing_m;   /* 0.005..0.2 */
	double mass_per_m_kg;    /* the colon with its contents, per m */
	double damping_n_s_per_m; /* b, per node */
	double chain_n_per_m;    /* k_c, between neighbours */
	double bending_n_per_m;  /* k_b, against crumpling */
};

#define FLEX_DEFAULT_NODE_SPACING_M 0.02
#define FLEX_DEFAULT_MASS_PER_M_KG 0.3 /* a guess: wall and contents */
#define FLEX_DEFAULT_DAMPING_N_S_PER_M 20
#define FLEX_DEFAULT_CHAIN_N_PER_M 100
#define FLEX_DEFAULT_BENDING_N_PER_M 300

#define FLEX_PARAMS_DEFAULT { \
	.node_spacing_m = FLEX_DEFAULT_NODE_SPACING_M, \
	.mass_per_m_kg = FLEX_DEFAULT_MASS_PER_M_KG, \
	.damping_n_s_per_m = FLEX_DEFAULT_DAMPING_N_S_PER_M, \
	.chain_n_per_m = FLEX_DEFAULT_CHAIN_N_PER_M, \
	.bending_n_per_m = FLEX_DEFAULT_BENDING_N_PER_M }

struct flex;

/* Room for the chains of any colon; none yet. NULL on bad parameters or
 * ENOMEM. */
struct flex *flex_create(const struct flex_params *p);

/*
 * The chains of COLON's mobile spans (those whose region has a mesentery,
 * FLEX_MAX_NODES nodes in all), at rest; the colon's centreline re-laid
 * to rest. COLON must outlive its attachment. No allocation: the force
 * loop may attach a new colon.
 */
void flex_attach(struct flex *f, struct colon *colon);

/* NULL is fine. */
void flex_destroy(struct flex *f);

/* Every node back at rest, the centreline too. */
void flex_reset(struct flex *f);

/* Live parameters (the node spacing stays as created). */
void flex_set_params(struct flex *f, const struct flex_params *p);

/* Gravity's acceleration G (m/s^2, world); zeros: none (the default). */
void flex_set_gravity(struct flex *f, const double g[3]);

/* The assistant's pad: a disc of radius RADIUS_M (its reach) about
 * POINT (m, world: the pad's face, pressed in) facing IN (unit, from the
 * abdominal wall into the abdomen), pressed with FORCE_N (N, > 0; 0: no
 * grip). */
struct flex_pad {
	bool on;
	double point[3];
	double in[3];
	double radius_m;
	double force_n;
};

/* How far a node held gives under the hand's whole force, m: a guess
 * (the grip's stiffness on each node held is force_n / FLEX_PAD_GIVE_M). */
#define FLEX_PAD_GIVE_M 0.005

/* The pad from the next step on (PAD->on false: none). Fixed work (the
 * nodes under it found when it changes); no allocation. */
void flex_set_pad(struct flex *f, const struct flex_pad *pad);

/* The force the pad held the colon with in the last step, N: the grip's
 * forces on the nodes added up (their magnitude), at most its force_n. */
double flex_pad_force(const struct flex *f);

/* Forgets the forces pushed since the last step. */
void flex_clear(struct flex *f);

/*
 * The tube pushes the wall at material S_M (m) with FORCE (N, world),
 * which eases by STIFFNESS (N/m, >= 0) per m the wall gives way (the
 * contact's spring: taken implicitly, so a stiff contact on a soft colon
 * stays stable); outside a mobile span the fixed colon takes it and
 * nothing moves.
 */
void flex_push(struct flex *f, double s_m, const double force[3],
	       double stiffness_n_per_m);

/* One step of DT_S seconds; re-lays the centreline where nodes moved. */
void flex_step(struct flex *f, double dt_s);

/* The wall's velocity at material S_M (m/s, world): 0 where fixed. */
void flex_velocity(const struct flex *f, double s_m, double v[3]);

/* Nodes in all, and in span SPAN (0 when it has none). */
int flex_nodes(const struct flex *f);
int flex_span_nodes(const struct flex *f, int span);

/* Node I's displacement from rest (m), spans in order. */
const double *flex_node(const struct flex *f, int i);

/*
 * Span SPAN's forces (N, world): PUSHED, what loaded it in the last step
 * (the tube's pushes and its weight); HELD, what holds it now: its
 * mesentery (across the course, and all of the load along it) and,
 * through the chain, the fixed colon at its ends. At rest, without the
 * pad, they are equal.
 */
void flex_span_forces(const struct flex *f, int span, double pushed[3],
		      double held[3]);

/* Span SPAN's largest node displacement from rest (m): the loop's size. */
double flex_span_displacement(const struct flex *f, int span);

/*
 * Span SPAN's mesentery tension (N): the sum over its nodes of the pull
 * of each one's mesentery, k_m (1 + (|y| / h)^2) |y|, what stretches it
 * where the colon is pushed off its course (pain.h). A span pushed
 * evenly, F on each of its nodes, holds its nodes' count times F at rest.
 */
double flex_span_tension(const struct flex *f, int span);

#endif
