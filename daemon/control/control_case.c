/* control_case.c - the control thread's scene and cases (control_private.h). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "conf/cases.h"
#include "control/control_private.h"
#include "model/scene.h"

#define SWAP_TIMEOUT_MS 500

struct control_cases {
	struct scene *scene;     /* GetScene's replies, made on demand */
	Endosim__CaseListReply case_list;
	Endosim__CaseEntry *case_entries;
	Endosim__CaseEntry **case_entries_p;
	struct cases_entry *cases;
	char case_error[512];    /* ListCases' */
	char error[256];         /* LoadCase's refusal */
};

struct control_cases *control_cases_create(void)
{
	return calloc(1, sizeof(struct control_cases));
}

/* Frees the case list the last reply was made of. */
static void free_case_list(struct control_cases *cs)
{
	free(cs->cases);
	free(cs->case_entries);
	free(cs->case_entries_p);
	cs->cases = NULL;
	cs->case_entries = NULL;
	cs->case_entries_p = NULL;
}

void control_cases_destroy(struct control_cases *cs)
{
	if (!cs) {
		return;
	}
	free_case_list(cs);
	scene_destroy(cs->scene);
	free(cs);
}

void control_on_get_scene(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__GetScene *g = req->get_scene;
	struct control_cases *cs = c->cases;
	Endosim__SceneReply *sr;

	(void)cl;
	if (g->chunk && g->scene_id != c->scene_id) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the case changed: start again from chunk 0");
		return;
	}
	if (!cs->scene) {
		cs->scene = scene_create(c->colon, c->scene_id);
		if (!cs->scene) {
			log_err("GetScene: out of memory");
			refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
			       "out of memory");
			return;
		}
	}
	if (!g->chunk) { /* the scope as it is now ([scope] is live) */
		struct scope_params sp;

		cases_scope_params(&c->cfg, &sp);
		scene_set_scope(cs->scene, &sp, c->cfg.haptics.scope_radius_m);
	}
	sr = scene_reply(cs->scene, g->chunk);
	if (!sr) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, "no such chunk");
		return;
	}
	rep->body_case = ENDOSIM__REPLY__BODY_SCENE;
	rep->scene = sr;
}

void control_on_list_cases(struct control *c, struct client *cl,
			   const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_cases *cs = c->cases;
	Endosim__CaseListReply *l = &cs->case_list;
	size_t n;

	(void)cl;
	(void)req;
	free_case_list(cs);
	if (cases_list(c->cfg.colon.directory, &cs->cases, &n, cs->case_error,
		       sizeof(cs->case_error))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, cs->case_error);
		return;
	}
	cs->case_entries = calloc(n + 1, sizeof(*cs->case_entries));
	cs->case_entries_p = calloc(n + 1, sizeof(*cs->case_entries_p));
	if (!cs->case_entries || !cs->case_entries_p) {
		free_case_list(cs);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, "out of memory");
		return;
	}
	for (size_t i = 0; i < n; i++) {
		Endosim__CaseEntry *e = &cs->case_entries[i];

		endosim__case_entry__init(e);
		e->name = cs->cases[i].name;
		e->description = cs->cases[i].description;
		e->loaded = !strcmp(e->name, colon_name(c->colon));
		cs->case_entries_p[i] = e;
	}
	endosim__case_list_reply__init(l);
	l->n_cases = n;
	l->cases = cs->case_entries_p;
	l->directory = c->cfg.colon.directory;
	l->error = cs->case_error;
	rep->body_case = ENDOSIM__REPLY__BODY_CASES;
	rep->cases = l;
}

/* Hands COLON to the loop; on success it is the one GetScene serves. */
static int swap_colon(struct control *c, struct colon *colon)
{
	struct colon *old = NULL;
	int r = loop_swap_colon(c->deps.loop, colon, c->scene_id + 1, &old,
				SWAP_TIMEOUT_MS);

	if (r) {
		colon_destroy(colon);
		return r;
	}
	scene_destroy(c->cases->scene);
	c->cases->scene = NULL;
	c->colon = colon;
	c->scene_id++;
	colon_destroy(old);
	return 0;
}

int control_load_case(struct control *c, struct client *cl,
		      const char *name, Endosim__Reply *rep)
{
	struct recorder_info ri;
	struct endosim_state st;
	struct colon *colon;
	int r;

	recorder_info(c->deps.recorder, &ri);
	if (ri.recording) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "a session is recording: 'session stop' first");
		return -1;
	}
	if (!publish_read(c->deps.pub, &st) &&
	    st.state != ENDOSIM_STATE_IDLE) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "a case loads only while IDLE: disable first");
		return -1;
	}
	colon = cases_load(&c->cfg, name, c->cases->error,
			   sizeof(c->cases->error));
	if (!colon) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->cases->error);
		return -1;
	}
	r = swap_colon(c, colon);
	if (r == -EBUSY) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "a case loads only while IDLE: disable first");
		return -1;
	}
	if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the new case");
		return -1;
	}
	cases_path(&c->cfg, name, c->case_path, sizeof(c->case_path));
	log_notice("case %s loaded (uid %d): %u triangles", name,
		   (int)cl->uid, colon_mesh(colon)->triangles);
	return 0;
}

void control_on_load_case(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	control_load_case(c, cl, req->load_case->name, rep);
}
