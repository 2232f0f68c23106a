/*
 * haptics_gains.h - the force model's gains, a plain struct that the
 * configuration's [haptics] section fills (config.h) and the model reads
 * (haptics.h), so that neither includes the other. Units in the names;
 * every key with its unit and range in `endosimd --print-config`.
 */
#ifndef ENDOSIM_HAPTICS_GAINS_H
#define ENDOSIM_HAPTICS_GAINS_H

#include "proto/endosim_shm.h"

/* [haptics] model: which model renders the forces (haptics.h). */
enum haptics_model {
	HAPTICS_MODEL_PAPER = 0, /* the paper's: the tube on the centreline */
	HAPTICS_MODEL_ROD = 1,   /* an elastic rod in a colon that moves */
};

struct haptics_gains {
	int model;                     /* enum haptics_model (not live) */
	double scope_radius_m;         /* the tip: the contact inset */
	double wall_stiffness_n_per_m;
	double wall_damping_n_s_per_m;
	double tip_lateral_stiffness_n_per_m; /* bending section */
	int force_shading;             /* 1: interpolated normals */
	double contact_reach_m;        /* colon searched around the tip */
	double entry_depth_m;          /* contact from this depth on */
	double friction_n_s_per_m_rad; /* c_f */
	double torsion_n_m_s_per_rad2; /* roll friction per turning */
	double wire_spacing_m;         /* dr */
	double wire_tension_n_m_per_m; /* k_t */
	double bending_stiffness_n_m_per_rad;
	double stop_stiffness_n_m_per_rad; /* each knob's end */
	double stop_damping_n_m_s_per_rad;
	double wheel_delay_s;          /* a drive's wheel: its lag */
	double loop_relax_s;           /* how fast a loop follows */
	double damping[ENDOSIM_AXES];  /* N s/m or N m s/rad */
	int passivity;                 /* 1: passivity observer on */
};

#endif
