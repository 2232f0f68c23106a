/*
 * control_guide.c - guided replay's commands (the Guide request): the session
 * file read into a path here, on the control thread; the loop gets the
 * path and the command (loop_guide()) and answers within a cycle or two.
 * The path the loop plays is kept here (struct control_guide) until a
 * later start replaces it.
 */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "control/control_private.h"
#include "rig/guide.h"
#include "session/sessiondir.h"

struct control_guide {
	struct guide_path *path;  /* the loop's (loop_guide()) */
	struct guide_path *limbo; /* handed over, never answered: freed at
				     the end */
	char error[256];
};

struct control_guide *control_guide_create(void)
{
	return calloc(1, sizeof(struct control_guide));
}

void control_guide_destroy(struct control_guide *g)
{
	if (!g) {
		return;
	}
	guide_path_free(g->path);
	guide_path_free(g->limbo);
	free(g);
}

/* The axes' positions of the newest published state; false if none. */
static bool positions(struct control *c, double q[ENDOSIM_AXES],
		      uint32_t *state)
{
	struct endosim_state st;

	if (publish_read(c->deps.pub, &st)) {
		return false;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		q[a] = st.axis[a].position;
	}
	*state = st.state;
	return true;
}

/* The path of the request's session, its case the loaded one; NULL with
 * REP refused. */
static struct guide_path *load_path(struct control *c,
				    const Endosim__Guide *g,
				    Endosim__Reply *rep)
{
	char *why = c->guide->error;
	size_t size = sizeof(c->guide->error);
	char file[2 * CONFIG_STR];
	struct guide_path *p;

	if (*g->file) {
		snprintf(file, sizeof(file), "%s", g->file);
	} else if (!g->session_id ||
		   sessiondir_path(c->cfg.session.directory, g->session_id,
				   file, sizeof(file))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "guide start: name a session (its id) or a file");
		return NULL;
	}
	p = guide_path_load(file, why, size);
	if (!p) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, why);
		return NULL;
	}
	if (*p->case_name && strcmp(p->case_name, colon_name(c->colon))) {
		snprintf(why, size, "guide start: session "
			 "%" PRIu64 " was recorded on case '%.63s', the loaded "
			 "case is '%.63s'", p->source_id, p->case_name,
			 colon_name(c->colon));
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED, why);
		guide_path_free(p);
		return NULL;
	}
	return p;
}

/* Hands CMD to the loop; a start's PATH becomes the one kept on 0. */
static void hand_over(struct control *c, const struct guide_command *cmd,
		      struct guide_path *path, Endosim__Reply *rep)
{
	struct control_guide *g = c->guide;
	int r = loop_guide(c->deps.loop, cmd, COMMAND_TIMEOUT_MS);

	if (r == 0 && path) {
		guide_path_free(g->path);
		g->path = path;
	} else if (r == -ETIMEDOUT && path) {
		/* the loop may take it yet: never freed while it runs */
		guide_path_free(g->limbo);
		g->limbo = path;
	} else if (path) {
		guide_path_free(path);
	}
	if (r == -EINVAL && cmd->action == GUIDE_TAKEOVER) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "guide: nothing to take over from");
	} else if (r == -EINVAL) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "guide: speed out of 0.25 .. 2, or a time outside the "
		       "recording");
	} else if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
	} else {
		control_await_state(c);
		control_build_status(c, rep);
	}
}

void control_on_guide(struct control *c, struct client *cl,
		      const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__Guide *g = req->guide;
	struct guide_command cmd = { .speed = 1 };
	struct guide_path *path = NULL;
	double q[ENDOSIM_AXES];
	uint32_t state;

	(void)cl;
	if (!positions(c, q, &state)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
		       "no published state to guide from");
		return;
	}
	if (g->action != ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_STOP &&
	    state != ENDOSIM_STATE_ENABLED) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "guide: the rig is not ENABLED: enable first");
		return;
	}
	switch (g->action) {
	case ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_START:
		path = load_path(c, g, rep);
		if (!path) {
			return;
		}
		cmd = (struct guide_command){
			.action = GUIDE_START, .path = path,
			.speed = g->speed > 0 ? g->speed : 1,
			.from_s = g->from_s,
		};
		log_notice("guide: session %" PRIu64 " from %.2f s at %.2fx",
			   path->source_id, cmd.from_s, cmd.speed);
		break;
	case ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_STOP:
		cmd.action = GUIDE_STOP;
		break;
	case ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_TAKEOVER:
		cmd.action = GUIDE_TAKEOVER;
		break;
	case ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESUME:
	case ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESET:
		if (!c->guide->path) {
			refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
			       "guide: nothing to resume: 'guide start' first");
			return;
		}
		cmd.action = g->action ==
			     ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESUME ?
			     GUIDE_RESUME : GUIDE_RESET;
		cmd.from_s = cmd.action == GUIDE_RESET && g->from_given ?
			     g->from_s : guide_path_nearest(c->guide->path, q);
		break;
	default:
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "guide: no such action");
		return;
	}
	hand_over(c, &cmd, path, rep);
}
