/*
 * endoctl_map.c - `endoctl session map`: the recording session's
 * unseen-mucosa map (SessionMap, either socket) as text or JSON
 * (endoctl.h).
 */
#include "endoctl/endoctl.h"

#include "session/livemap.h"

/* A cell as a character: ' ' no wall, '.' unseen .. '#' all seen. */
static char cell_char(uint8_t cell)
{
	double v = livemap_share(cell);

	return v < 0 ? ' ' : v < 0.1 ? '.' : v < 0.5 ? ':' : v < 0.9 ? '+'
								      : '#';
}

/* The column of S_M (m along) on a map of ALONG cells over LENGTH_M. */
static long map_column(double s_m, double length_m, uint32_t along)
{
	long i = length_m > 0 ? lround(floor(s_m / length_m * along)) : 0;

	return i < 0 ? 0 : i >= (long)along ? (long)along - 1 : i;
}

/* Under the rows: each region's start (its initial), the tip (^). */
static void print_marks(const Endosim__MapReply *m)
{
	char line[1024];
	uint32_t n = m->along < sizeof(line) - 1 ? m->along : sizeof(line) - 1;

	memset(line, ' ', n);
	line[n] = '\0';
	for (size_t i = 0; i < m->n_regions; i++) {
		line[map_column(m->regions[i]->s0_m, m->length_m, n)] =
			m->regions[i]->name[0];
	}
	line[map_column(m->tip_s_m, m->length_m, n)] = '^';
	printf("     %s\n", line);
}

static void print_map(const Endosim__MapReply *m)
{
	printf("session %" PRIu64 " at %.1f s: %.1f %% of the mucosa seen; "
	       "the colon (%.2f m) unrolled, %u cells along by %u around\n"
	       "('#' seen, '+' most, ':' some, '.' unseen; under it each "
	       "segment's start, '^' the tip at %.3f m)\n", m->session_id,
	       m->time_s, 100 * m->mucosa_seen, m->length_m, m->along,
	       m->around, m->tip_s_m);
	for (uint32_t k = 0; k < m->around; k++) {
		printf("%3u  ", k * 360 / m->around);
		for (uint32_t i = 0; i < m->along; i++) {
			putchar(cell_char(m->cells.data[i * m->around + k]));
		}
		putchar('\n');
	}
	print_marks(m);
	for (size_t i = 0; i < m->n_regions; i++) {
		printf("%s%c %s", i ? ", " : "segments: ",
		       m->regions[i]->name[0], m->regions[i]->name);
	}
	printf("\npolyps found: %zu\n", m->n_found);
	for (size_t i = 0; i < m->n_found; i++) {
		printf("  polyp %u at %.3f m, %.0f deg\n",
		       m->found[i]->index + 1, m->found[i]->s_m,
		       m->found[i]->angle_rad * 180 / M_PI);
	}
}

static void json_map(const Endosim__MapReply *m)
{
	struct json j;

	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_uint(&j, "session_id", m->session_id);
	json_double(&j, "time_s", m->time_s);
	json_double(&j, "length_m", m->length_m);
	json_uint(&j, "along", m->along);
	json_uint(&j, "around", m->around);
	json_double(&j, "mucosa_seen", m->mucosa_seen);
	json_double(&j, "cells_seen",
		    livemap_mean_seen(m->cells.data, m->cells.len));
	json_double(&j, "tip_s_m", m->tip_s_m);
	json_array_begin(&j, "regions");
	for (size_t i = 0; i < m->n_regions; i++) {
		json_object_begin(&j, NULL);
		json_string(&j, "name", m->regions[i]->name);
		json_double(&j, "s0_m", m->regions[i]->s0_m);
		json_double(&j, "s1_m", m->regions[i]->s1_m);
		json_object_end(&j);
	}
	json_array_end(&j);
	json_array_begin(&j, "found");
	for (size_t i = 0; i < m->n_found; i++) {
		json_object_begin(&j, NULL);
		json_uint(&j, "index", m->found[i]->index);
		json_double(&j, "s_m", m->found[i]->s_m);
		json_double(&j, "angle_rad", m->found[i]->angle_rad);
		json_object_end(&j);
	}
	json_array_end(&j);
	json_array_begin(&j, "cells"); /* along, each around: 0..254, 255 */
	for (uint32_t i = 0; i < m->along; i++) {
		json_array_begin(&j, NULL);
		for (uint32_t k = 0; k < m->around; k++) {
			json_uint(&j, NULL, m->cells.data[i * m->around + k]);
		}
		json_array_end(&j);
	}
	json_array_end(&j);
	json_object_end(&j);
}

int ctl_session_map(struct ctl *ctl)
{
	Endosim__SessionMap body = ENDOSIM__SESSION_MAP__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	const Endosim__MapReply *m;
	Endosim__Reply *rep;
	int r;

	req.body_case = ENDOSIM__REQUEST__BODY_SESSION_MAP;
	req.session_map = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	m = rep->body_case == ENDOSIM__REPLY__BODY_MAP ? rep->map : NULL;
	if (!m || (size_t)m->along * m->around != m->cells.len) {
		fprintf(stderr, "endoctl: a map reply that does not add up\n");
		endosim__reply__free_unpacked(rep, NULL);
		return EXIT_COMM;
	}
	if (ctl->json) {
		json_map(m);
	} else {
		print_map(m);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}
