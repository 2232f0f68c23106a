/* control_case.c - the control thread's scene and cases (control_private.h). */
#include "control/control_private.h"

void control_on_get_scene(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__GetScene *g = req->get_scene;
	Endosim__SceneReply *sr;

	(void)cl;
	if (g->chunk && g->scene_id != c->scene_id) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the case changed: start again from chunk 0");
		return;
	}
	if (!c->scene) {
		c->scene = scene_create(c->colon, c->scene_id);
		if (!c->scene) {
			log_err("GetScene: out of memory");
			refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
			       "out of memory");
			return;
		}
	}
	if (!g->chunk) { /* the scope as it is now ([scope] is live) */
		struct scope_params sp;

		cases_scope_params(&c->cfg, &sp);
		scene_set_scope(c->scene, &sp, c->cfg.haptics.scope_radius_m);
	}
	sr = scene_reply(c->scene, g->chunk);
	if (!sr) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, "no such chunk");
		return;
	}
	rep->body_case = ENDOSIM__REPLY__BODY_SCENE;
	rep->scene = sr;
}

void control_free_case_list(struct reply_buf *rb)
{
	free(rb->cases);
	free(rb->case_entries);
	free(rb->case_entries_p);
	rb->cases = NULL;
	rb->case_entries = NULL;
	rb->case_entries_p = NULL;
}

void control_on_list_cases(struct control *c, struct client *cl,
			   const Endosim__Request *req, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	Endosim__CaseListReply *l = &rb->case_list;
	size_t n;

	(void)cl;
	(void)req;
	control_free_case_list(rb);
	if (cases_list(c->cfg.colon.directory, &rb->cases, &n, rb->case_error,
		       sizeof(rb->case_error))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->case_error);
		return;
	}
	rb->case_entries = calloc(n + 1, sizeof(*rb->case_entries));
	rb->case_entries_p = calloc(n + 1, sizeof(*rb->case_entries_p));
	if (!rb->case_entries || !rb->case_entries_p) {
		control_free_case_list(rb);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, "out of memory");
		return;
	}
	for (size_t i = 0; i < n; i++) {
		Endosim__CaseEntry *e = &rb->case_entries[i];

		endosim__case_entry__init(e);
		e->name = rb->cases[i].name;
		e->description = rb->cases[i].description;
		e->loaded = !strcmp(e->name, colon_name(c->colon));
		rb->case_entries_p[i] = e;
	}
	endosim__case_list_reply__init(l);
	l->n_cases = n;
	l->cases = rb->case_entries_p;
	l->directory = c->cfg.colon.directory;
	l->error = rb->case_error;
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
	scene_destroy(c->scene);
	c->scene = NULL;
	c->colon = colon;
	c->scene_id++;
	colon_destroy(old);
	return 0;
}

/* Loads case NAME (IDLE only, never during a session). 0, or -1 refused. */
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
	colon = cases_load(&c->cfg, name, c->rb.error, sizeof(c->rb.error));
	if (!colon) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->rb.error);
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
