/* state_text.c - see state_text.h. */
#include "state_text.h"

static void doubles(FILE *f, const char *prefix, const char *key,
		    const double *v, int n)
{
	fprintf(f, "%s%s=", prefix, key);
	for (int i = 0; i < n; i++) {
		fprintf(f, "%s%.9g", i ? "," : "", v[i]);
	}
	fputc('\n', f);
}

static void axes(FILE *f, const char *prefix, const struct endosim_state *st)
{
	static const char *const keys[] = { "position", "velocity", "hand",
					    "command", "limited" };
	double v[ENDOSIM_AXES];

	for (int k = 0; k < 5; k++) {
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			const struct endosim_axis_state *ax = &st->axis[a];
			const double all[] = { ax->position, ax->velocity,
					       ax->hand, ax->command,
					       ax->limited };

			v[a] = all[k];
		}
		doubles(f, prefix, keys[k], v, ENDOSIM_AXES);
	}
}

static void scope(FILE *f, const char *prefix,
		  const struct endosim_scope_state *sc)
{
	fprintf(f, "%sdepth_m=%.9g\n%sroll_rad=%.9g\n", prefix, sc->depth_m,
		prefix, sc->roll_rad);
	doubles(f, prefix, "bend_rad", sc->bend_rad, 2);
	fprintf(f, "%sbase_s_m=%.9g\n%stip_s_m=%.9g\n%sturning_rad=%.9g\n",
		prefix, sc->base_s_m, prefix, sc->tip_s_m, prefix,
		sc->turning_rad);
	doubles(f, prefix, "tip", sc->tip, 3);
	doubles(f, prefix, "dir", sc->dir, 3);
	doubles(f, prefix, "up", sc->up, 3);
	doubles(f, prefix, "bow_m", sc->bow_m, ENDOSIM_SPANS);
	fprintf(f, "%sspans=%u\n", prefix, sc->spans);
}

static void haptics(FILE *f, const char *prefix,
		    const struct endosim_haptics_state *h)
{
	doubles(f, prefix, "proxy", h->proxy, 3);
	doubles(f, prefix, "normal", h->normal, 3);
	doubles(f, prefix, "f_static", h->f_static, 3);
	fprintf(f, "%spenetration_m=%.9g\n%scontact=%u\n", prefix,
		h->penetration_m, prefix, h->contact);
}

static void tube(FILE *f, const char *prefix,
		 const struct endosim_scope_state *sc)
{
	fprintf(f, "%stube=", prefix);
	for (int i = 0; i < ENDOSIM_TUBE_POINTS; i++) {
		fprintf(f, "%s%.9g,%.9g,%.9g", i ? ";" : "", sc->tube[i][0],
			sc->tube[i][1], sc->tube[i][2]);
	}
	fputc('\n', f);
}

void state_text_print(FILE *f, const char *prefix,
		      const struct endosim_state *st)
{
	fprintf(f, "%scycle=%llu\n%sstamp_ns=%llu\n%sstate=%u\n"
		"%sfault_bits=%u\n%sscenario_time_s=%.9g\n", prefix,
		(unsigned long long)st->cycle, prefix,
		(unsigned long long)st->stamp_ns, prefix, st->state, prefix,
		st->fault_bits, prefix, st->scenario_time_s);
	axes(f, prefix, st);
	fprintf(f, "%sramp=%.9g\n", prefix, st->safety.ramp);
	scope(f, prefix, &st->scope);
	haptics(f, prefix, &st->haptics);
	tube(f, prefix, &st->scope);
}
