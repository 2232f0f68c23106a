/*
 * model.h - the colon as endoview holds it: the scene that GetScene served
 * (proto/client.h), rebuilt with the daemon's own modules (centreline.h,
 * mesh.h) so that a bowed mobile segment is placed exactly as the haptics
 * place it.
 *
 * The scope is the scene's (the shipped one, scope.h, from a daemon that
 * does not say). The centreline is made from the scene's undeformed
 * samples and first frame, the mobile spans from its span table; the mesh
 * from each vertex' sample and offset, finished (mesh_finish()) into the
 * same vertex and triangle order and the same segment table as the
 * daemon's, with the scene's normals. model_bow() then bows the spans to
 * the amplitudes the
 * force loop publishes (struct endosim_scope_state bow_m) with
 * centreline_bow() and mesh_place(), as colon_bow() does in the daemon;
 * in the rod model model_displace() moves them through the nodes it
 * publishes (struct endosim_rod_state) with centreline_displace(), as the
 * daemon's colon follows them (flex.h). model_scale() widens or narrows
 * the lumen by the gas's factors (the patient's body, gas.h). The case's
 * sites where the assistant presses (SceneSite) are kept as the scene
 * orders them, the order of the published hand_site.
 *
 * A view that draws only some vertices (lod.h) says which with
 * model_keep(): from then on those two place the others only for the
 * segments' bounding boxes (mesh_place_kept(): the boxes stay the
 * daemon's), their pos and nrm left as they were; model_wall() and
 * model_wall_gap() place the vertices they read as they go.
 *
 * Main thread only. model_create() allocates; the rest does not.
 */
#ifndef ENDOVIEW_MODEL_H
#define ENDOVIEW_MODEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "model/centreline.h"
#include "proto/client.h"
#include "proto/endosim_shm.h"
#include "model/mesh.h"
#include "model/scope.h"

#define MODEL_NAME 64
#define MODEL_MAX_REGIONS 16
#define MODEL_MAX_POLYPS 32
#define MODEL_MAX_SITES 8
#define MODEL_BOW_STEP_M 0.0005 /* smaller changes of a bow or a node are
				   not placed */
#define MODEL_SCALE_STEP 0.005  /* a lumen factor that changed by a smaller
				   share is not placed again */
#define MODEL_END_M 0.15        /* the cecum's dome: a camera stays where */
#define MODEL_OPEN 0.6          /* the lumen is this share of its widest in
				   the last MODEL_END_M */

struct model_region {
	char name[MODEL_NAME]; /* "sigmoid", ...; "colon" for an import */
	double s0_m, s1_m;
	int span;              /* its mobile span, -1 if fixed */
	double max_bow_m;      /* the mesentery's height (mobile only) */
};

enum model_polyp_shape {
	MODEL_POLYP_SESSILE = 0,
	MODEL_POLYP_PEDUNCULATED,
	MODEL_POLYP_FLAT,
};

struct model_polyp {
	double s_m;        /* from the anal verge */
	double angle_rad;  /* around the lumen from the frame's u */
	double diameter_m;
	int shape;         /* enum model_polyp_shape */
};

/* A place on the abdomen where the assistant presses (SceneSite). */
struct model_site {
	char name[MODEL_NAME]; /* "llq", "umbilical", ... */
	double position_m[3];  /* the pad's centre, body frame */
	double direction[3];   /* into the abdomen (unit) */
	double radius_m;
};

struct model {
	uint64_t scene_id;
	char name[MODEL_NAME];
	struct scope_params scope; /* the scope the daemon renders with */
	double scope_radius_m;     /* its tip's and tube's */
	struct centreline *cl;
	struct mesh *mesh;
	uint32_t ring;     /* vertices per ring of a generated tube; 0 if not */
	struct model_region region[MODEL_MAX_REGIONS];
	int regions;
	struct model_polyp polyp[MODEL_MAX_POLYPS];
	int polyps;
	struct model_site site[MODEL_MAX_SITES]; /* the scene's order: the
						    published hand_site */
	int sites;
	double placed_error_m; /* largest distance from the scene's vertices */
	size_t last_open;  /* the last sample whose ring is wide open */
	/* the rod model's nodes as last placed, each span's from
	   node_first[k] (node_count[k] of them; 0: the span is bowed) */
	double node[ENDOSIM_COLON_NODES][3];
	int node_first[CENTRELINE_MAX_SPANS], node_count[CENTRELINE_MAX_SPANS];
	const uint8_t *keep; /* the vertices kept placed (NULL: all) */
};

/*
 * Builds the model of scene S (which the caller still owns and may free
 * afterwards). NULL with one line in ERR on a scene that does not add up
 * (e.g. a segment table that differs from the daemon's) or ENOMEM.
 */
struct model *model_create(const struct client_scene *s, char *err,
			   size_t errsize);

/* NULL is fine. */
void model_destroy(struct model *m);

/* From now on model_bow() and model_displace() keep only the vertices
 * KEEP marks placed (one byte per vertex, non-zero: kept; NULL: all, as
 * model_create() leaves it). KEEP must outlive its use. */
void model_keep(struct model *m, const uint8_t *keep);

/*
 * Bows span k (0 <= k < SPANS) to BOW_M[k] wherever it differs from the
 * placed one by MODEL_BOW_STEP_M or more, and places the vertices that
 * move. Returns the vertices moved as [*FIRST, *FIRST + *COUNT) (count 0:
 * none), for the caller to upload.
 */
void model_bow(struct model *m, const double *bow_m, int spans,
	       uint32_t *first, uint32_t *count);

/*
 * The rod model's colon: moves span k by its ROD->span_nodes[k] nodes
 * (spans in order, span 0's first in ROD->node) wherever one of them
 * differs from the placed one by MODEL_BOW_STEP_M or more, and places the
 * vertices that move. A span without nodes, or whose nodes are not all
 * there or not finite, stays as it is. Returns the vertices moved as
 * model_bow() does.
 */
void model_displace(struct model *m, const struct endosim_rod_state *rod,
		    uint32_t *first, uint32_t *count);

/*
 * The gas's lumen: scales the mesh radially about the centreline by
 * FACTOR (per anatomical segment, as published in struct
 * endosim_patient_state; NULL: 1), blended across the segments'
 * boundaries as the haptics blend it (gas_factor_in()): one surface for
 * the picture and the contact. Each sample whose factor differs from the
 * one it is placed with by MODEL_SCALE_STEP of it or more (or that
 * comes back to 1: the case's lumen exactly) is placed again, with the
 * bows and nodes as they are; a factor that is not
 * finite or not positive counts as 1. A colon without the nine segments
 * (an import) stays as it is. Returns the vertices moved as model_bow()
 * does.
 */
void model_scale(struct model *m, const double *factor, uint32_t *first,
		 uint32_t *count);

/*
 * How far (m) the centreline of mobile span SPAN lies from its rest at
 * most, bowed or moved by nodes; *AT (when not NULL) that sample.
 */
double model_moved(const struct model *m, int span, size_t *at);

/* Whether P (m) lies outside the patient: behind the anal verge's normal
 * plane, in the rig's pipe (rodscope.h). */
bool model_outside(const struct model *m, const float p[3]);

/* The region holding S_M (clamped to the colon). */
const struct model_region *model_region_at(const struct model *m,
					   double s_m);

/* The centreline sample nearest the material position S_M. */
size_t model_sample_at(const struct model *m, double s_m);

/*
 * The wall at sample I towards ANGLE_RAD (around the lumen from the
 * frame's u), as placed now: the point P (m) and the unit normal N into
 * the lumen. For a mesh that is not a generated tube, the ring's vertex
 * nearest that direction.
 */
void model_wall(const struct model *m, size_t i, double angle_rad,
		double p[3], double n[3]);

/*
 * How far P (m) lies inside the wall (negative: outside), measured from
 * the centreline in the plane of the sample near *I whose normal plane
 * passes nearest P; *I becomes that sample (a hint for the next point).
 * With D, the unit direction from the centreline to P in that plane.
 */
double model_wall_gap(const struct model *m, size_t *i, const double p[3],
		      double d[3]);

/*
 * Keeps P (m) inside the lumen near sample I: a point farther from the
 * centreline than the wall less MARGIN_M in its direction is pulled
 * towards the centreline until it is not, and one past the plane of
 * sample last_open (into the cecum's dome) back onto that plane. Returns
 * how far it moved (m).
 */
double model_keep_inside(const struct model *m, size_t i, double p[3],
			 double margin_m);

#endif
