/* link.c - see link.h. */
#include "viewer/link.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "proto/shm_reader.h"
#include "session/sessioninputs.h"
#include "viewer/reconnect.h"

#define READ_TRIES 8

struct link {
	/* the read-only socket, a connection for each fetch of the scene (at
	   most every LINK_RETRY_S); its problem is the link's */
	struct reconnect *scene;
	char shm_name[128];
	struct shm_reader *shm;
	uint64_t start_ns; /* of the daemon whose state we hold */
	struct endosim_state st;
	bool have_state;
	bool changed;
	uint64_t next_open_ns;  /* earliest time to try to open again */
	double loop_config_m;   /* [session] loop_threshold_m; 0: by model */
	double relief_pa;       /* [patient] relief_pa; 0: none or not told */
	double strength_n_per_m; /* [patient] wall_strength_n_per_m; 0: not
				    told */
};

struct link *link_create(const char *socket, const char *shm_name)
{
	struct link *l = calloc(1, sizeof(*l));

	if (!l) {
		return NULL;
	}
	snprintf(l->shm_name, sizeof(l->shm_name), "%s",
		 shm_name ? shm_name : ENDOSIM_SHM_DEFAULT_NAME);
	l->scene = reconnect_create(socket, false, LINK_RETRY_S, LOG_NOTICE,
				    "");
	if (!l->scene) {
		free(l);
		return NULL;
	}
	return l;
}

void link_destroy(struct link *l)
{
	if (!l) {
		return;
	}
	shm_reader_close(l->shm);
	reconnect_destroy(l->scene);
	free(l);
}

static void try_open(struct link *l, uint64_t now_ns)
{
	uint64_t start;

	l->next_open_ns = now_ns + (uint64_t)(LINK_RETRY_S * ENDOSIM_NS_PER_S);
	l->shm = shm_reader_open(l->shm_name);
	if (!l->shm) {
		reconnect_say(l->scene, errno == ENOENT ?
			      "no endosimd: no shared memory %s" :
			      "shared memory %s: %s", l->shm_name,
			      errno == EPROTO ? "another layout version" :
						strerror(errno));
		return;
	}
	start = shm_reader_header(l->shm)->start_ns;
	if (l->have_state && start != l->start_ns) {
		l->changed = true; /* a new daemon: its scene ids start again */
	}
	l->start_ns = start;
	reconnect_clear(l->scene);
}

/* Stale: is its writer gone, or has another daemon replaced it? */
static enum link_status check_stale(struct link *l, uint64_t now_ns)
{
	if (!shm_reader_writer_alive(l->shm)) {
		reconnect_say(l->scene, "endosimd (pid %d) is gone",
			      (int)shm_reader_header(l->shm)->writer_pid);
		shm_reader_close(l->shm);
		l->shm = NULL;
		return LINK_NO_DAEMON;
	}
	if (now_ns >= l->next_open_ns) {
		struct shm_reader *old = l->shm;

		try_open(l, now_ns);
		if (!l->shm) {
			l->shm = old; /* nothing newer: keep what we have */
			reconnect_clear(l->scene);
		} else {
			shm_reader_close(old);
		}
	}
	return LINK_STALE;
}

enum link_status link_update(struct link *l, uint64_t now_ns)
{
	struct endosim_state st;

	if (!l->shm && now_ns >= l->next_open_ns) {
		try_open(l, now_ns);
	}
	if (!l->shm) {
		return LINK_NO_DAEMON;
	}
	if (shm_reader_read(l->shm, &st, READ_TRIES) == 0) {
		l->st = st;
		l->have_state = true;
	}
	if (!l->have_state) {
		return LINK_NO_DAEMON;
	}
	if (link_stale_s(l, now_ns) > LINK_STALE_S) {
		return check_stale(l, now_ns);
	}
	return LINK_LIVE;
}

const struct endosim_state *link_state(const struct link *l)
{
	return l->have_state ? &l->st : NULL;
}

double link_stale_s(const struct link *l, uint64_t now_ns)
{
	int64_t age = (int64_t)now_ns - (int64_t)l->st.publish_ns;

	return l->have_state && age > 0 ? (double)age / ENDOSIM_NS_PER_S : 0;
}

const char *link_problem(const struct link *l)
{
	return reconnect_problem(l->scene);
}

bool link_scene_wanted(const struct link *l, uint64_t held_id,
		       uint64_t now_ns)
{
	return l->shm && l->have_state && l->st.scope.scene_id &&
	       l->st.scope.scene_id != held_id &&
	       reconnect_due(l->scene, now_ns);
}

/* The daemon's configuration value KEY ("session.loop_threshold_m"),
 * asked on C; 0 when it does not say. */
static double ask_config(struct client *c, const char *key)
{
	Endosim__GetConfig body = ENDOSIM__GET_CONFIG__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	double v = 0;

	body.key = (char *)key;
	req.body_case = ENDOSIM__REQUEST__BODY_GET_CONFIG;
	req.get_config = &body;
	if (client_request(c, &req, &rep, LINK_SCENE_TIMEOUT_MS)) {
		return 0;
	}
	if (rep->status == ENDOSIM__STATUS__STATUS_OK &&
	    rep->body_case == ENDOSIM__REPLY__BODY_CONFIG &&
	    rep->config->n_entries == 1) {
		v = strtod(rep->config->entries[0]->value, NULL);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return isfinite(v) ? v : 0;
}

/* What the viewer takes from the daemon's configuration with a scene. */
static void ask_configuration(struct link *l, struct client *c)
{
	l->loop_config_m = ask_config(c, "session.loop_threshold_m");
	l->relief_pa = ask_config(c, "patient.relief_pa");
	l->strength_n_per_m = ask_config(c, "patient.wall_strength_n_per_m");
}

int link_fetch_scene(struct link *l, struct client_scene **out,
		     uint64_t now_ns)
{
	Endosim__Status status = ENDOSIM__STATUS__STATUS_OK;
	int r;

	reconnect_now(l->scene); /* asked: fetched; the delay that this
				    starts is for link_scene_wanted() */
	r = reconnect_connect(l->scene, now_ns);
	if (r < 0) {
		reconnect_say(l->scene, "scene: %s: %s",
			      reconnect_path(l->scene), strerror(-r));
		return r;
	}
	r = client_get_scene(reconnect_client(l->scene), out,
			     LINK_SCENE_TIMEOUT_MS, &status);
	if (!r) {
		ask_configuration(l, reconnect_client(l->scene));
	}
	reconnect_close(l->scene);
	if (r) {
		reconnect_say(l->scene, "scene from %s: %s",
			      reconnect_path(l->scene),
			      r == -EACCES ? client_status_text(status) :
					     strerror(-r));
		return r;
	}
	reconnect_clear(l->scene);
	return 0;
}

double link_loop_threshold_m(const struct link *l)
{
	return sessioninputs_loop_threshold_m(l->loop_config_m,
					      l->have_state &&
					      l->st.rod.model ==
					      ENDOSIM_MODEL_ROD);
}

void link_patient_limits(const struct link *l, double *relief_pa,
			 double *strength_n_per_m)
{
	*relief_pa = l->relief_pa;
	*strength_n_per_m = l->strength_n_per_m;
}

bool link_daemon_changed(struct link *l)
{
	bool changed = l->changed;

	l->changed = false;
	return changed;
}
