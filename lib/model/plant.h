/*
 * plant.h - one axis of the simulated rig: a mass (or inertia) with viscous
 * and Coulomb friction between two hard end stops.
 *
 *   m dv/dt = F - b v - Fc sign(v),   |F| <= Fc holds a resting axis
 *
 * plant_step() integrates one period exactly for a force held constant over
 * the step (zero-order hold, as a drive applies a setpoint): the viscous part
 * by its exponential solution, the Coulomb part piecewise around the moment
 * the velocity reaches zero. Linear axes in m, N, kg; rotary axes in rad,
 * N m, kg m^2. Pure computation: safe in the force loop.
 */
#ifndef ENDOSIM_PLANT_H
#define ENDOSIM_PLANT_H

struct plant_params {
	double inertia;  /* kg or kg m^2, > 0 */
	double viscous;  /* N s/m or N m s/rad, >= 0 */
	double coulomb;  /* N or N m, >= 0 */
	double min, max; /* end stops, m or rad */
};

struct plant {
	struct plant_params p;
	double x; /* position, m or rad */
	double v; /* velocity, m/s or rad/s */
};

/* At rest at X0 (clamped into the travel). */
void plant_init(struct plant *pl, const struct plant_params *p, double x0);

/*
 * Advances by DT seconds under the external force FORCE (N or N m). At an end
 * stop the axis stops dead (a fully inelastic hard stop).
 */
void plant_step(struct plant *pl, double force, double dt);

#endif
