/* scenario.c - see scenario.h. */
#include "rig/scenario.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/parse.h"
#include "proto/names.h"

/* Each kind of line's record; each starts with its time (struct list). */
struct step {
	double t;     /* s */
	int axis;
	enum scenario_mode mode;
	double value; /* m, rad, N or N m */
	double ramp;  /* s */
	double from;  /* target in effect when a target step starts */
};

struct valve_step {
	double t;
	uint32_t valve; /* enum endosim_valve bit */
	bool on;
};

struct patient_step {
	double t;
	struct scenario_patient cmd; /* its seq is the player's */
};

union record {
	struct step step;
	struct valve_step valve;
	struct patient_step patient;
};

/* Records of SIZE bytes, each starting with its time (a double). */
struct list {
	char *v;
	size_t count;
	size_t cap;
	size_t size;
};

struct scenario {
	struct list steps;   /* struct step: the axes' */
	struct list valves;  /* struct valve_step */
	struct list patient; /* struct patient_step */
	double end_t;        /* INFINITY when neither end nor repeat */
	bool repeat;
};

enum line_kind { LINE_STEP, LINE_VALVE, LINE_PATIENT, LINE_END };

/* One line parsed. */
struct line {
	enum line_kind kind;
	bool repeat;         /* LINE_END: repeat rather than end */
	union record r;
};

static void *list_at(const struct list *l, size_t i)
{
	return l->v + i * l->size;
}

static double list_t(const struct list *l, size_t i)
{
	return *(const double *)list_at(l, i);
}

/* The time of the list's last record, 0 when it has none. */
static double list_last_t(const struct list *l)
{
	return l->count ? list_t(l, l->count - 1) : 0;
}

static int list_add(struct list *l, const void *rec)
{
	if (l->count == l->cap) {
		size_t n = l->cap ? l->cap * 2 : 16;
		char *grown = realloc(l->v, n * l->size);

		if (!grown) {
			return -ENOMEM;
		}
		l->v = grown;
		l->cap = n;
	}
	memcpy(list_at(l, l->count++), rec, l->size);
	return 0;
}

/* Orders the records by time, keeping the file's order for equal times. */
static void list_sort(struct list *l)
{
	union record r;

	for (size_t i = 1; i < l->count; i++) {
		size_t j = i;

		memcpy(&r, list_at(l, i), l->size);
		for (; j > 0 && list_t(l, j - 1) > r.step.t; j--) {
			memcpy(list_at(l, j), list_at(l, j - 1), l->size);
		}
		memcpy(list_at(l, j), &r, l->size);
	}
}

static int parse_mode(struct step *st, char **tok, int ntok, char *why,
		      size_t size)
{
	const char *mode = tok[2];

	if (!strcmp(mode, "free") && ntok == 3) {
		st->mode = SCENARIO_FREE;
		return 0;
	}
	if (!strcmp(mode, "force") && ntok == 4) {
		st->mode = SCENARIO_FORCE;
	} else if (!strcmp(mode, "target") && (ntok == 4 || ntok == 5)) {
		st->mode = SCENARIO_TARGET;
		if (ntok == 5 && (parse_double(tok[4], &st->ramp) ||
				  st->ramp < 0)) {
			snprintf(why, size, "ramp '%s' is not a duration in s",
				 tok[4]);
			return -EINVAL;
		}
	} else {
		snprintf(why, size, "expected 'target VALUE [RAMP]', "
			 "'force VALUE' or 'free'");
		return -EINVAL;
	}
	if (parse_double(tok[3], &st->value)) {
		snprintf(why, size, "'%s' is not a number", tok[3]);
		return -EINVAL;
	}
	return 0;
}

/* "valve air|water|suction on|off" */
static int parse_valve(struct valve_step *v, char **tok, int ntok, char *why,
		       size_t size)
{
	if (ntok != 4 || (strcmp(tok[3], "on") && strcmp(tok[3], "off"))) {
		snprintf(why, size, "expected 'valve air|water|suction "
			 "on|off'");
		return -EINVAL;
	}
	v->valve = names_valve_find(tok[2]);
	v->on = !strcmp(tok[3], "on");
	if (!v->valve) {
		snprintf(why, size, "unknown valve '%s' (air, water or "
			 "suction)", tok[2]);
		return -EINVAL;
	}
	return 0;
}

/* "press SITE [N]" */
static int parse_press(struct scenario_patient *c, char **tok, int ntok,
		       char *why, size_t size)
{
	c->action = SCENARIO_PATIENT_PRESS;
	if (strlen(tok[3]) >= sizeof(c->site)) {
		snprintf(why, size, "site name '%.32s...' too long", tok[3]);
		return -EINVAL;
	}
	strcpy(c->site, tok[3]);
	if (ntok == 5 && (parse_double(tok[4], &c->force_n) ||
			  !(c->force_n > 0))) {
		snprintf(why, size, "'%s' is not a force in N", tok[4]);
		return -EINVAL;
	}
	return 0;
}

/* "patient position NAME", "patient press SITE [N]", "patient release" */
static int parse_patient(struct scenario_patient *c, char **tok, int ntok,
			 char *why, size_t size)
{
	const char *act = ntok > 2 ? tok[2] : "";

	if (!strcmp(act, "position") && ntok == 4) {
		c->action = SCENARIO_PATIENT_TURN;
		c->position = names_position_find(tok[3]);
		if (c->position < 0) {
			snprintf(why, size, "unknown position '%s' "
				 "(left-lateral, supine, right-lateral or "
				 "prone)", tok[3]);
			return -EINVAL;
		}
		return 0;
	}
	if (!strcmp(act, "press") && (ntok == 4 || ntok == 5)) {
		return parse_press(c, tok, ntok, why, size);
	}
	if (!strcmp(act, "release") && ntok == 3) {
		c->action = SCENARIO_PATIENT_RELEASE;
		return 0;
	}
	snprintf(why, size, "expected 'patient position NAME', 'patient "
		 "press SITE [N]' or 'patient release'");
	return -EINVAL;
}

/* What follows the time: an axis' step, a valve or the patient. */
static int parse_what(struct line *ln, char **tok, int ntok, char *why,
		      size_t size)
{
	if (!strcmp(tok[1], "valve")) {
		ln->kind = LINE_VALVE;
		return parse_valve(&ln->r.valve, tok, ntok, why, size);
	}
	if (!strcmp(tok[1], "patient")) {
		ln->kind = LINE_PATIENT;
		return parse_patient(&ln->r.patient.cmd, tok, ntok, why, size);
	}
	ln->kind = LINE_STEP;
	ln->r.step.axis = names_axis_find(tok[1]);
	if (ln->r.step.axis < 0) {
		snprintf(why, size, "unknown axis '%s'", tok[1]);
		return -EINVAL;
	}
	return parse_mode(&ln->r.step, tok, ntok, why, size);
}

/* Parses one non-empty line into LN. */
static int parse_line(struct line *ln, char *text, char *why, size_t size)
{
	char *tok[6], *save = NULL;
	int ntok = 0;

	for (char *t = strtok_r(text, " \t\r\n", &save); t;
	     t = strtok_r(NULL, " \t\r\n", &save)) {
		if (ntok == 6) {
			snprintf(why, size, "too many fields");
			return -EINVAL;
		}
		tok[ntok++] = t;
	}
	memset(ln, 0, sizeof(*ln));
	if (parse_double(tok[0], &ln->r.step.t) || ln->r.step.t < 0) {
		snprintf(why, size, "'%s' is not a time in s", tok[0]);
		return -EINVAL;
	}
	if (ntok == 2 && (!strcmp(tok[1], "end") || !strcmp(tok[1], "repeat"))) {
		ln->kind = LINE_END;
		ln->repeat = !strcmp(tok[1], "repeat");
		return 0;
	}
	if (ntok < 3) {
		snprintf(why, size, "expected 'TIME AXIS MODE ...', 'TIME "
			 "valve ...', 'TIME patient ...' or 'TIME "
			 "end|repeat'");
		return -EINVAL;
	}
	return parse_what(ln, tok, ntok, why, size);
}

/* The line's time (each record starts with it). */
static double line_t(const struct line *ln)
{
	return ln->r.step.t;
}

static struct list *list_of(struct scenario *s, enum line_kind kind)
{
	return kind == LINE_VALVE ? &s->valves :
	       kind == LINE_PATIENT ? &s->patient : &s->steps;
}

/* The latest time any line has. */
static double last_t(const struct scenario *s)
{
	return fmax(list_last_t(&s->steps), fmax(list_last_t(&s->valves),
						 list_last_t(&s->patient)));
}

static size_t lines(const struct scenario *s)
{
	return s->steps.count + s->valves.count + s->patient.count;
}

/* Links each target step to the target before it, for its ramp. */
static void link_targets(struct scenario *s)
{
	double target[ENDOSIM_AXES] = { 0 };

	for (size_t i = 0; i < s->steps.count; i++) {
		struct step *st = list_at(&s->steps, i);

		if (st->mode == SCENARIO_TARGET) {
			st->from = target[st->axis];
			target[st->axis] = st->value;
		}
	}
}

static int parse_file(struct scenario *s, FILE *f, const char *path,
		      char *err, size_t errsize)
{
	char text[256], why[128];
	struct line ln;
	int lineno = 0, end_line = 0;

	while (fgets(text, sizeof(text), f)) {
		lineno++;
		text[strcspn(text, "#")] = '\0';
		if (strspn(text, " \t\r\n") == strlen(text)) {
			continue;
		}
		if (end_line) {
			return parse_error(err, errsize, path, lineno, NULL,
					   "a step after the end/repeat on "
					   "line %d", end_line);
		}
		if (parse_line(&ln, text, why, sizeof(why))) {
			return parse_error(err, errsize, path, lineno, NULL,
					   "%s", why);
		}
		if (ln.kind == LINE_END) {
			s->end_t = line_t(&ln);
			s->repeat = ln.repeat;
			end_line = lineno;
		} else if (list_add(list_of(s, ln.kind), &ln.r)) {
			parse_error(err, errsize, path, 0, NULL,
				    "out of memory");
			return -ENOMEM;
		}
	}
	if (!lines(s)) {
		return parse_error(err, errsize, path, 0, NULL, "no steps");
	}
	return 0;
}

/* A scenario that ends must not have steps after its end. */
static int check_end(const struct scenario *s, const char *path, char *err,
		     size_t errsize)
{
	double last = last_t(s);

	if (isfinite(s->end_t) && last > s->end_t) {
		snprintf(err, errsize, "%s: a step at %g s is after the "
			 "end/repeat at %g s", path, last, s->end_t);
		return -EINVAL;
	}
	return 0;
}

struct scenario *scenario_create(void)
{
	struct scenario *s = calloc(1, sizeof(*s));

	if (s) {
		s->steps.size = sizeof(struct step);
		s->valves.size = sizeof(struct valve_step);
		s->patient.size = sizeof(struct patient_step);
		s->end_t = INFINITY;
	}
	return s;
}

struct scenario *scenario_load_stream(FILE *f, const char *name, char *err,
				      size_t errsize)
{
	struct scenario *s = scenario_create();
	int r;

	if (!s) {
		snprintf(err, errsize, "%s: out of memory", name);
		return NULL;
	}
	r = parse_file(s, f, name, err, errsize);
	if (!r) {
		list_sort(&s->steps);
		list_sort(&s->valves);
		list_sort(&s->patient);
		r = check_end(s, name, err, errsize);
	}
	if (r) {
		scenario_destroy(s);
		return NULL;
	}
	link_targets(s);
	return s;
}

struct scenario *scenario_load(const char *path, char *err, size_t errsize)
{
	struct scenario *s;
	FILE *f = fopen(path, "r");

	if (!f) {
		snprintf(err, errsize, "%s: cannot open: %s", path,
			 strerror(errno));
		return NULL;
	}
	s = scenario_load_stream(f, path, err, errsize);
	fclose(f);
	return s;
}

int scenario_append(struct scenario *s, const char *text, char *err,
		    size_t errsize)
{
	char buf[256], why[128];
	struct line ln;

	snprintf(buf, sizeof(buf), "%s", text);
	buf[strcspn(buf, "#")] = '\0';
	if (isfinite(s->end_t)) {
		snprintf(err, errsize, "'%s': after the end/repeat", text);
		return -EINVAL;
	}
	if (parse_line(&ln, buf, why, sizeof(why))) {
		snprintf(err, errsize, "'%s': %s", text, why);
		return -EINVAL;
	}
	if (line_t(&ln) < last_t(s)) {
		snprintf(err, errsize, "'%s': before the last step", text);
		return -EINVAL;
	}
	if (ln.kind == LINE_END) {
		s->end_t = line_t(&ln);
		s->repeat = ln.repeat;
		return 0;
	}
	if (list_add(list_of(s, ln.kind), &ln.r)) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	link_targets(s);
	return 0;
}

void scenario_destroy(struct scenario *s)
{
	if (!s) {
		return;
	}
	free(s->steps.v);
	free(s->valves.v);
	free(s->patient.v);
	free(s);
}

static double local_time(const struct scenario *s, double t)
{
	if (s->repeat && s->end_t > 0) {
		return fmod(t, s->end_t);
	}
	return t;
}

void scenario_eval(const struct scenario *s, double t,
		   struct scenario_cmd out[ENDOSIM_AXES])
{
	t = local_time(s, t);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		out[a].mode = SCENARIO_FREE;
		out[a].value = 0;
	}
	for (size_t i = 0; i < s->steps.count && list_t(&s->steps, i) <= t;
	     i++) {
		const struct step *st = list_at(&s->steps, i);
		struct scenario_cmd *c = &out[st->axis];

		c->mode = st->mode;
		c->value = st->value;
		if (st->mode == SCENARIO_TARGET && t < st->t + st->ramp) {
			double f = (t - st->t) / st->ramp;

			c->value = st->from + f * (st->value - st->from);
		}
	}
}

uint32_t scenario_valves(const struct scenario *s, double t)
{
	uint32_t bits = 0;

	t = local_time(s, t);
	for (size_t i = 0; i < s->valves.count && list_t(&s->valves, i) <= t;
	     i++) {
		const struct valve_step *v = list_at(&s->valves, i);

		bits = v->on ? bits | v->valve : bits & ~v->valve;
	}
	return bits;
}

uint32_t scenario_patient_due(const struct scenario *s, double t)
{
	double local = local_time(s, t);
	uint32_t due = 0;

	if (s->repeat && s->end_t > 0 && isfinite(t)) {
		/* the rounds a repeat has played, as local_time() counts */
		double rounds = round((t - local) / s->end_t);

		due = (uint32_t)fmin(fmax(rounds, 0), UINT32_MAX) *
		      (uint32_t)s->patient.count;
	}
	for (size_t i = 0; i < s->patient.count &&
			   list_t(&s->patient, i) <= local; i++) {
		due++;
	}
	return due;
}

void scenario_patient_get(const struct scenario *s, uint32_t seq,
			  struct scenario_patient *out)
{
	size_t n = s->patient.count;

	memset(out, 0, sizeof(*out));
	if (!seq || !n || (!s->repeat && seq > n)) {
		return;
	}
	*out = ((const struct patient_step *)list_at(&s->patient,
						     (seq - 1) % n))->cmd;
	out->seq = seq;
}

bool scenario_done(const struct scenario *s, double t)
{
	return !s->repeat && t >= s->end_t;
}

double scenario_length(const struct scenario *s)
{
	double len = last_t(s);

	if (isfinite(s->end_t)) {
		return s->end_t;
	}
	for (size_t i = 0; i < s->steps.count; i++) {
		const struct step *st = list_at(&s->steps, i);

		len = fmax(len, st->t + st->ramp);
	}
	return len;
}
