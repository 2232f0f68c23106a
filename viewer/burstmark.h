/*
 * burstmark.h - where the patient's first wall would burst, for the
 * pressure gauge (patientview.h): an estimate from what the daemon
 * publishes (struct endosim_patient_state), the viewer knowing neither
 * the walls' laws nor their widest rings (gas.h has the model).
 *
 * Pure computation, any thread.
 */
#ifndef ENDOVIEW_BURSTMARK_H
#define ENDOVIEW_BURSTMARK_H

#include "proto/endosim_shm.h"

#define BURSTMARK_PA_PER_MMHG 133.322387415

/*
 * The gas pressure (Pa above the atmosphere) at which the first wall of P
 * would tear at its present width: for each segment with a positive
 * transmural pressure p_i and its wall's tension t_i (Laplace's p_i r_i,
 * r_i = t_i / p_i), the pressure that makes p r reach STRENGTH (N/m,
 * [patient] wall_strength_n_per_m), the gas's P less p_i being the
 * abdomen's pressure on it; the least of them. A wall widens as the gas
 * rises, so the mark comes down to the truth as the pressure nears it.
 * NAN when no wall is distended or STRENGTH is not known (<= 0).
 */
double burstmark_pa(const struct endosim_patient_state *p,
		    double strength_n_per_m);

#endif
