/* scenario.c - see scenario.h. */
#include "rig/scenario.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/parse.h"
#include "proto/names.h"

struct step {
	double t;     /* s */
	int axis;
	enum scenario_mode mode;
	double value; /* m, rad, N or N m */
	double ramp;  /* s */
	double from;  /* target in effect when a target step starts */
};

struct scenario {
	struct step *steps;
	size_t count;
	size_t cap;    /* steps' room */
	double end_t;  /* INFINITY when neither end nor repeat */
	bool repeat;
};

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

/* Parses one non-empty line into ST, or into the end marker of S. */
static int parse_line(struct scenario *s, struct step *st, char *line,
		      char *why, size_t size)
{
	char *tok[6], *save = NULL;
	int ntok = 0;

	for (char *t = strtok_r(line, " \t\r\n", &save); t;
	     t = strtok_r(NULL, " \t\r\n", &save)) {
		if (ntok == 6) {
			snprintf(why, size, "too many fields");
			return -EINVAL;
		}
		tok[ntok++] = t;
	}
	memset(st, 0, sizeof(*st));
	if (parse_double(tok[0], &st->t) || st->t < 0) {
		snprintf(why, size, "'%s' is not a time in s", tok[0]);
		return -EINVAL;
	}
	if (ntok == 2 && (!strcmp(tok[1], "end") || !strcmp(tok[1], "repeat"))) {
		s->end_t = st->t;
		s->repeat = !strcmp(tok[1], "repeat");
		return 1;
	}
	if (ntok < 3) {
		snprintf(why, size, "expected 'TIME AXIS MODE ...' or "
			 "'TIME end|repeat'");
		return -EINVAL;
	}
	st->axis = names_axis_find(tok[1]);
	if (st->axis < 0) {
		snprintf(why, size, "unknown axis '%s'", tok[1]);
		return -EINVAL;
	}
	return parse_mode(st, tok, ntok, why, size);
}

/* Links each target step to the target before it, for its ramp. */
static void link_targets(struct scenario *s)
{
	double target[ENDOSIM_AXES] = { 0 };

	for (size_t i = 0; i < s->count; i++) {
		struct step *st = &s->steps[i];

		if (st->mode == SCENARIO_TARGET) {
			st->from = target[st->axis];
			target[st->axis] = st->value;
		}
	}
}

static int add_step(struct scenario *s, const struct step *st)
{
	if (s->count == s->cap) {
		size_t n = s->cap ? s->cap * 2 : 16;
		struct step *grown = realloc(s->steps, n * sizeof(*grown));

		if (!grown) {
			return -ENOMEM;
		}
		s->steps = grown;
		s->cap = n;
	}
	s->steps[s->count++] = *st;
	return 0;
}

static int parse_file(struct scenario *s, FILE *f, const char *path,
		      char *err, size_t errsize)
{
	char line[256], why[128];
	struct step st;
	int lineno = 0, end_line = 0, r;

	while (fgets(line, sizeof(line), f)) {
		lineno++;
		line[strcspn(line, "#")] = '\0';
		if (strspn(line, " \t\r\n") == strlen(line)) {
			continue;
		}
		if (end_line) {
			return parse_error(err, errsize, path, lineno, NULL,
					   "a step after the end/repeat on "
					   "line %d", end_line);
		}
		r = parse_line(s, &st, line, why, sizeof(why));
		if (r < 0) {
			return parse_error(err, errsize, path, lineno, NULL,
					   "%s", why);
		}
		if (r == 1) {
			end_line = lineno;
		} else if (add_step(s, &st)) {
			parse_error(err, errsize, path, 0, NULL,
				    "out of memory");
			return -ENOMEM;
		}
	}
	if (!s->count) {
		return parse_error(err, errsize, path, 0, NULL, "no steps");
	}
	return 0;
}

/* Orders the steps by time, keeping the file's order for equal times. */
static void sort_steps(struct scenario *s)
{
	for (size_t i = 1; i < s->count; i++) {
		struct step st = s->steps[i];
		size_t j = i;

		for (; j > 0 && s->steps[j - 1].t > st.t; j--) {
			s->steps[j] = s->steps[j - 1];
		}
		s->steps[j] = st;
	}
}

/* A scenario that ends must not have steps after its end. */
static int check_end(const struct scenario *s, const char *path, char *err,
		     size_t errsize)
{
	const struct step *last = &s->steps[s->count - 1];

	if (isfinite(s->end_t) && last->t > s->end_t) {
		snprintf(err, errsize, "%s: a step at %g s is after the "
			 "end/repeat at %g s", path, last->t, s->end_t);
		return -EINVAL;
	}
	return 0;
}

struct scenario *scenario_load_stream(FILE *f, const char *name, char *err,
				      size_t errsize)
{
	struct scenario *s = calloc(1, sizeof(*s));
	int r;

	if (!s) {
		snprintf(err, errsize, "%s: out of memory", name);
		return NULL;
	}
	s->end_t = INFINITY;
	r = parse_file(s, f, name, err, errsize);
	if (!r) {
		sort_steps(s);
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
	char line[256], why[128];
	struct step st;
	int r;

	snprintf(line, sizeof(line), "%s", text);
	line[strcspn(line, "#")] = '\0';
	if (isfinite(s->end_t)) {
		snprintf(err, errsize, "'%s': after the end/repeat", text);
		return -EINVAL;
	}
	r = parse_line(s, &st, line, why, sizeof(why));
	if (r < 0) {
		snprintf(err, errsize, "'%s': %s", text, why);
		return r;
	}
	if (s->count && ((r == 1 ? s->end_t : st.t) <
			 s->steps[s->count - 1].t)) {
		snprintf(err, errsize, "'%s': before the last step", text);
		if (r == 1) {
			s->end_t = INFINITY;
		}
		return -EINVAL;
	}
	if (r == 1) {
		return 0;
	}
	if (add_step(s, &st)) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	link_targets(s);
	return 0;
}

struct scenario *scenario_create(void)
{
	struct scenario *s = calloc(1, sizeof(*s));

	if (s) {
		s->end_t = INFINITY;
	}
	return s;
}

void scenario_destroy(struct scenario *s)
{
	if (!s) {
		return;
	}
	free(s->steps);
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
	for (size_t i = 0; i < s->count && s->steps[i].t <= t; i++) {
		const struct step *st = &s->steps[i];
		struct scenario_cmd *c = &out[st->axis];

		c->mode = st->mode;
		c->value = st->value;
		if (st->mode == SCENARIO_TARGET && t < st->t + st->ramp) {
			double f = (t - st->t) / st->ramp;

			c->value = st->from + f * (st->value - st->from);
		}
	}
}

bool scenario_done(const struct scenario *s, double t)
{
	return !s->repeat && t >= s->end_t;
}

double scenario_length(const struct scenario *s)
{
	double len = 0;

	if (isfinite(s->end_t)) {
		return s->end_t;
	}
	for (size_t i = 0; i < s->count; i++) {
		len = fmax(len, s->steps[i].t + s->steps[i].ramp);
	}
	return len;
}
