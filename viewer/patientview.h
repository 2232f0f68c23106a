/*
 * patientview.h - the patient panel's pictures (the HUD's, hud.h): where
 * the patient lies as a small figure, and the gas's pressure as a gauge.
 *
 * The figure is the body's cross-section seen from the feet: a torso
 * (PATIENTVIEW_BODY_* wide and deep, the shipped cases' frame: x to the
 * patient's left, y posterior) with the belly's bulge in front and the
 * spine behind, its left and right flanks lettered L and R, on the
 * table, turned so that the published gravity
 * (struct endosim_patient_state down) points down the screen: left
 * lateral lies on its left side, supine on its back, and a turn in
 * progress shows the body part way round. The assistant's hand, while it
 * presses, is an arrow at its site (the scene's, struct model_site)
 * pushing along the site's direction.
 *
 * The gauge is a dial from 0 to PATIENTVIEW_GAUGE_MMHG: the gas's pressure
 * above the atmosphere as a needle and a filled arc (green, amber past
 * the relief or PATIENTVIEW_HIGH_MMHG, red past the burst mark), the
 * insufflator's relief as a white mark (none: no relief), and where the
 * first wall would burst (burstmark.h) as a red mark and a red
 * arc beyond it (none when it lies beyond the dial).
 *
 * Main thread; the drawing functions queue into D (draw2d.h) between
 * draw2d_begin() and draw2d_end().
 */
#ifndef ENDOVIEW_PATIENTVIEW_H
#define ENDOVIEW_PATIENTVIEW_H

#include "proto/endosim_shm.h"
#include "viewer/draw2d.h"
#include "viewer/model.h"

#define PATIENTVIEW_GAUGE_MMHG 120.0 /* the dial's full scale */
#define PATIENTVIEW_HIGH_MMHG 60.0   /* above the free tip's 9-57
					(Kozarek): amber */
#define PATIENTVIEW_BODY_W_M 0.34    /* the figure's torso, left to right */
#define PATIENTVIEW_BODY_D_M 0.24    /* and front to back */
#define PATIENTVIEW_BODY_Y_M (-0.09) /* its centre's y (the sites' frame) */

/*
 * The figure of P centred at (CX, CY) pixels, SIZE pixels across; its
 * hand's site from M (NULL, or a site it does not hold: no arrow).
 */
void patientview_figure(struct draw2d *d, float cx, float cy, float size,
			const struct endosim_patient_state *p,
			const struct model *m);

/*
 * The gauge centred at (CX, CY), RADIUS pixels, for PRESSURE_PA with the
 * marks RELIEF_PA (<= 0: none) and BURST_PA (NAN: none); its text in
 * the centre with D's small font.
 */
void patientview_gauge(struct draw2d *d, float cx, float cy, float radius,
		       double pressure_pa, double relief_pa, double burst_pa);

#endif
