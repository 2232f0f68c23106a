/*
 * endoview - the colonoscopy simulator's monitor: the endoscopic image, the
 * scope's shape in the colon, the forces, and the trainee's hands on the
 * simulated rig. See docs/TRAINEE.md and docs/ARCHITECTURE.md.
 *
 *   endoview [--socket PATH] [--shm-name NAME] [--view endo|overview|both]
 *            [--size WxH] [--screenshot FILE.png] [--frames N]
 *            [--no-vsync] [--max-fps N] [--font FILE.ttf] [--stats]
 *            [--mute] [--voice DIR] [--trainee NAME | --no-login]
 *            [--print-state] [--replay FILE [--seek S] [--speed X] [--paused]]
 *
 * A separate process: it only reads the daemon's shared memory and asks
 * the sockets, so whatever happens to it, the force loop goes on. Where
 * the rig's accounts hold a trainee, it asks who is training (login.h,
 * loginview.h) and logs them out when it quits, if it logged them in. With
 * --replay it plays a recorded session instead (replay.h), with no daemon
 * and no socket. The patient's voice (voice.h) sounds through the audio
 * device (sound.h); without one, endoview says so once and goes on
 * silent. Each clip said is logged ("voice: ow, pain 5.6, at 9.683 s,
 * 10.012 s of sound": the live or the replay's clock, and the time since
 * the audio device opened, a wave file's under test).
 *
 * Exit status: 0 done; 1 no window, an OpenGL error, the screenshot could
 * not be written, or a session file that cannot be replayed; 2 usage.
 */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "viewer/draw2d.h"
#include "viewer/endo.h"
#include "viewer/font.h"
#include "viewer/gfx.h"
#include "viewer/gpumesh.h"
#include "viewer/hud.h"
#include "viewer/imagescale.h"
#include "viewer/input.h"
#include "viewer/lensfx.h"
#include "viewer/link.h"
#include "viewer/lod.h"
#include "viewer/login.h"
#include "viewer/loginview.h"
#include "base/log.h"
#include "viewer/mapview.h"
#include "viewer/model.h"
#include "base/mono.h"
#include "viewer/overview.h"
#include "viewer/replay.h"
#include "viewer/rigctl.h"
#include "viewer/shot.h"
#include "viewer/sound.h"
#include "proto/names.h"
#include "proto/state_text.h"
#include "viewer/timing.h"
#include "viewer/ui.h"
#include "viewer/viewopts.h"
#include "viewer/viewstats.h"
#include "viewer/voice.h"

#define HAND_HOLD_MS 250 /* a hand input outlives a few lost frames */
#define VALVE_HOLD_MS 1000 /* held valves outlive a slow frame or two */
#define LAPSE_MS 1 /* let go: the live input lapses at once */
#define WARM_UP_FRAMES 3  /* not counted after start-up or a new colon */
#define COMPACT_PANEL_PX 320 /* a narrower panel shows the essentials */
#define HEADLESS_FRAME_S (1.0 / 60) /* a replay's step per frame with --frames */
#define REPLAY_MAX_STEP_S 0.25      /* the clock skips no more after a stall */
#define CHART_STEP_S (HUD_CHART_S / 200) /* a replay's chart: one record per */

/* The colon as fetched, in its three forms. */
struct colon_set {
	struct model *model;
	struct lod *lod;
	struct gpumesh *gpu;
};

struct app {
	struct viewopts opt;
	GLFWwindow *window;
	struct link *link;      /* live; NULL in a replay */
	struct rigctl *rig;     /* live; NULL in a replay */
	struct replay *replay;  /* NULL: live */
	struct hud_replay hr;
	struct ui *ui;
	struct font *font;
	struct draw2d *d2d;
	struct endo *endo;
	struct lensfx *lensfx;
	struct imagescale *scale; /* the image, offscreen and scaled up */
	struct imagescale *overscale; /* the overview, offscreen */
	double image_scale;       /* of each side: 1 full size */
	struct overview *overview;
	struct hud *hud;
	struct mapview *mapview; /* the M key's overlay */
	struct voice voice;      /* what the patient says */
	struct sound *sound;     /* NULL: silent */
	char voice_line[160];    /* the panel's line about it */
	struct timing *timing;
	struct colon_set colon;
	struct input_hand hand;
	struct overview_orbit orbit;
	struct login login;     /* who is training */
	bool logged_in_here;    /* this viewer logged the trainee in */
	enum link_status status;
	bool loading, help, map_shown;
	uint32_t triangles, triangles_max;
	uint64_t last_swap_ns, start_ns;
	uint64_t frame_due_ns; /* --max-fps: the next frame not before */
	uint64_t hand_ns; /* when the hand was last moved */
	uint32_t valves; /* the valves last sent held */
	uint64_t replay_ns; /* the replay's clock last run on */
	const struct endosim_state *shown; /* in the last frame */
	bool overview_shown;    /* the last frame drew the overview */
	bool endo_shown;        /* ... the endoscopic view: */
	struct endo_camera cam; /* from this camera */
	struct endo_rect endo_rect; /* into this (GL's origin) */
	long frame;
	long timed_from; /* the first frame the figures count */
	uint64_t pass_ns; /* --pass-times: when the last pass finished */
};

/* ------------------------------------------------------------ window */

static void on_glfw_error(int code, const char *text)
{
	log_err("GLFW (0x%x): %s", code, text);
}

static GLFWwindow *open_window(const struct viewopts *o)
{
	GLFWwindow *w;

	glfwSetErrorCallback(on_glfw_error);
	if (!glfwInit()) {
		log_err("no window system (is DISPLAY set?)");
		return NULL;
	}
	glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
	glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
	glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
	glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
	/* screenshots are for tests: have each GL error reported as it happens */
	glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT,
		       o->screenshot ? GLFW_TRUE : GLFW_FALSE);
	glfwWindowHint(GLFW_VISIBLE, o->screenshot ? GLFW_FALSE : GLFW_TRUE);
	/* the endoscopic view (and the benchmark's empty frame) without depth
	 * or stencil: its image is drawn offscreen and copied in, and the
	 * window's clear has no depth to clear; the overview draws in the
	 * window itself, or offscreen once a key shows it here
	 * (imagescale.h) */
	if (o->view == HUD_VIEW_ENDO || o->view == VIEWOPTS_VIEW_EMPTY) {
		glfwWindowHint(GLFW_DEPTH_BITS, 0);
		glfwWindowHint(GLFW_STENCIL_BITS, 0);
	}
	w = glfwCreateWindow(o->width, o->height, "endoview", NULL, NULL);
	if (!w) {
		log_err("no OpenGL 3.3 core context");
		glfwTerminate();
		return NULL;
	}
	glfwMakeContextCurrent(w);
	glfwSwapInterval(o->vsync ? 1 : 0);
	gfx_debug_init();
	log_info("OpenGL %s on %s", glGetString(GL_VERSION),
		 glGetString(GL_RENDERER));
	return w;
}

static int make_renderers(struct app *a)
{
	float small, large;

	hud_font_px(a->opt.height, &small, &large);
	a->font = font_create(a->opt.font, small, large);
	if (!a->font) {
		log_warn("font %s: %s: the HUD has no text", a->opt.font,
			 strerror(errno));
	}
	a->d2d = draw2d_create(a->font);
	a->endo = endo_create();
	a->lensfx = lensfx_create();
	a->scale = imagescale_create();
	a->overscale = imagescale_create();
	a->image_scale = a->opt.image_scale > 0 ?
		a->opt.image_scale :
		imagescale_for((const char *)glGetString(GL_RENDERER));
	if (a->image_scale < 1) {
		log_info("the endoscopic image drawn at %.0f %% of its size "
			 "and scaled up (--image-scale 1: full)",
			 100 * a->image_scale);
	}
	a->overview = overview_create();
	a->hud = hud_create();
	a->mapview = mapview_create(a->opt.socket, a->replay != NULL);
	a->timing = timing_create();
	a->ui = ui_create(a->window);
	if (!a->d2d || !a->endo || !a->lensfx || !a->scale || !a->overscale ||
	    !a->overview || !a->hud || !a->mapview || !a->timing || !a->ui) {
		log_err("cannot set up the views");
		return -ENOMEM;
	}
	return 0;
}

static void colon_free(struct colon_set *c)
{
	gpumesh_destroy(c->gpu);
	lod_destroy(c->lod);
	model_destroy(c->model);
	memset(c, 0, sizeof(*c));
}

/* Builds what draws scene S (the caller keeps S). 0 or -1, logged. */
static int build_colon(struct app *a, const struct client_scene *s)
{
	struct colon_set c = { 0 };
	char err[256];

	c.model = model_create(s, err, sizeof(err));
	if (!c.model) {
		log_err("%s", err);
		return -1;
	}
	c.lod = lod_create(c.model->mesh, c.model->ring);
	c.gpu = c.lod ? gpumesh_create(c.model, c.lod) : NULL;
	if (!c.gpu) {
		log_err("%s: cannot draw its mesh", c.model->name);
		colon_free(&c);
		return -1;
	}
	model_keep(c.model, c.lod->drawn); /* what the views draw */
	colon_free(&a->colon);
	a->colon = c;
	a->timed_from = a->frame + WARM_UP_FRAMES;
	log_info("colon %s: %u triangles, %u segments, %s", c.model->name,
		 c.model->mesh->triangles, c.model->mesh->segments,
		 c.model->ring ? "levels of detail" : "one level (imported)");
	return 0;
}

/* Fetches the scene the state names and builds what draws it. */
static void load_colon(struct app *a, uint64_t now)
{
	struct client_scene *s = NULL;

	if (link_fetch_scene(a->link, &s, now)) {
		return;
	}
	build_colon(a, s);
	client_scene_free(s);
}

/* ------------------------------------------------------------ frame */

/* The colon is the one the state is about: bow it, or move it by the rod
 * model's nodes, and widen its lumen by the gas, as the state says. */
static bool colon_current(struct app *a, const struct endosim_state *st)
{
	const struct endosim_scope_state *sc = st ? &st->scope : NULL;
	uint32_t first, count;

	if (!a->colon.model || !sc ||
	    sc->scene_id != a->colon.model->scene_id) {
		return false;
	}
	if (st->rod.model == ENDOSIM_MODEL_ROD) {
		model_displace(a->colon.model, &st->rod, &first, &count);
	} else {
		model_bow(a->colon.model, sc->bow_m,
			  (int)(sc->spans < ENDOSIM_SPANS ? sc->spans :
							    ENDOSIM_SPANS),
			  &first, &count);
	}
	gpumesh_update(a->colon.gpu, a->colon.model, first, count);
	model_scale(a->colon.model, st->patient.enabled ? st->patient.factor :
							  NULL,
		    &first, &count);
	gpumesh_update(a->colon.gpu, a->colon.model, first, count);
	return true;
}

static void update_link(struct app *a, uint64_t now)
{
	uint64_t held = a->colon.model ? a->colon.model->scene_id : 0;

	a->status = link_update(a->link, now);
	if (link_daemon_changed(a->link)) {
		held = 0; /* a new daemon's scene ids start again */
		colon_free(&a->colon);
		rigctl_trainee_now(a->rig); /* and nobody trains there yet */
	}
	if (a->loading) {
		load_colon(a, now);
		a->loading = false;
	} else if (a->status == LINK_LIVE &&
		   link_scene_wanted(a->link, held, now)) {
		a->loading = true; /* after a frame that says so */
	}
}

/* A replay's keys and timeline. */
static void act_replay(struct replay *r, const struct ui_actions *act)
{
	double speed = replay_speed(r);

	if (act->toggle_pause) {
		replay_set_paused(r, !replay_paused(r));
	}
	for (int k = 0; k < act->speed_steps; k++) {
		speed *= 2;
	}
	for (int k = 0; k > act->speed_steps; k--) {
		speed /= 2;
	}
	replay_set_speed(r, speed);
	replay_seek(r, act->seek_home ? 0 :
		       act->seek_end ? replay_duration(r) :
		       act->seek_to >= 0 ? act->seek_to * replay_duration(r) :
					   replay_time(r) + act->seek_by_s);
}

static void act(struct app *a, const struct ui_actions *act, uint64_t now)
{
	for (int k = 0; a->rig && k < RIGCTL_COMMANDS; k++) {
		if (act->command[k]) {
			rigctl_command(a->rig, (enum rigctl_command)k, now);
		}
	}
	if (a->replay) {
		act_replay(a->replay, act);
	}
	if (act->next_view) {
		a->opt.view = (a->opt.view + 1) % HUD_VIEWS;
	}
	if (act->toggle_help) {
		a->help = !a->help;
	}
	if (act->toggle_map) {
		a->map_shown = !a->map_shown;
	}
	if (act->toggle_mute) {
		a->opt.mute = !a->opt.mute;
		voice_set_muted(&a->voice, a->opt.mute);
		log_info("voice %s", a->opt.mute ? "muted" : "on");
	}
	if (act->reset_orbit) {
		a->orbit = (struct overview_orbit){ .zoom = 1 };
	}
	if (act->hands_off && a->rig) {
		a->hand.engaged = false;
		rigctl_hands_off(a->rig, now);
		log_info("hands off");
	}
}

/*
 * The trainee's hand, while the daemon is there to take it: its force
 * while the grip holds, the valves while a key holds them (with the
 * grip's force; alone when it does not hold, leaving a scenario's hand
 * driving), and once more when the last valve is let go, lapsing at
 * once, so that the gas stops with the key.
 */
static void drive(struct app *a, const struct input_controls *c,
		  const struct endosim_state *st, uint64_t now)
{
	double force[ENDOSIM_AXES], dt;
	bool grip;

	if (!st || a->status != LINK_LIVE) {
		a->hand.engaged = false;
		return;
	}
	dt = a->hand_ns ? (double)(now - a->hand_ns) / ENDOSIM_NS_PER_S : 0;
	a->hand_ns = now;
	if (a->login.stage == LOGIN_ASK) {
		a->hand.engaged = false; /* the form: nothing drives */
		return;
	}
	grip = input_step(&a->hand, c, st, fmin(dt, 0.1), now, force);
	if (grip || c->valves || a->valves) {
		rigctl_hand(a->rig, grip ? force : NULL, c->valves,
			    c->valves ? VALVE_HOLD_MS :
			    grip      ? HAND_HOLD_MS :
					LAPSE_MS, now);
	}
	a->valves = c->valves;
}

/* ------------------------------------------------------------ login */

/* The form's name and PIN sent: who trains now, or the refusal shown. */
static void send_login(struct app *a, uint64_t now)
{
	struct login *l = &a->login;
	char trainee[256] = "", words[256];

	if (rigctl_login(a->rig, l->name, l->pin, now, trainee, words,
			 sizeof(words))) {
		log_info("login of %s refused: %s", l->name, words);
		login_refused(l, words);
		return;
	}
	a->logged_in_here = true;
	login_accepted(l, trainee);
}

/* C: who trains logs out; the form asks for the next. */
static void send_logout(struct app *a, uint64_t now)
{
	char words[256];

	if (rigctl_logout(a->rig, now, words, sizeof(words))) {
		log_info("logout refused: %s", words);
		return;
	}
	a->logged_in_here = false;
	login_daemon(&a->login, true, "");
}

static void log_stage(const struct login *l, enum login_stage was)
{
	if (l->stage == was) {
		return;
	}
	if (l->stage == LOGIN_ASK) {
		log_info("login: who is training? (the login screen)");
	} else if (l->stage == LOGIN_IN) {
		log_info("login: %s trains at the rig", l->trainee);
	} else {
		log_info("login: nobody asked (no trainee's account, or no "
			 "daemon)");
	}
}

/*
 * Who is training: what the daemon says (every second), what was typed
 * into the form in order (each Enter that completes it sends the login),
 * --trainee's login once the daemon answers, C's logout.
 */
static void update_login(struct app *a, const struct ui_actions *act,
			 uint64_t now)
{
	struct login *l = &a->login;
	enum login_stage was = l->stage;
	char trainee[ACCOUNTS_NAME_MAX + 1];
	bool asks = false;
	int r;

	r = rigctl_trainee(a->rig, now, &asks, trainee, sizeof(trainee));
	if (r == 1) {
		login_daemon(l, asks, trainee);
	} else if (r < 0 && a->status == LINK_NO_DAEMON) {
		login_daemon(l, false, ""); /* a slow answer changes nothing */
	}
	for (int k = 0; k < act->n_typed; k++) {
		uint32_t c = act->typed[k];

		if (c < UI_TYPED_KEY) {
			login_type(l, c);
		} else if (login_key(l, (enum login_key)(c - UI_TYPED_KEY))) {
			send_login(a, now);
		}
	}
	if (login_scripted(l)) {
		send_login(a, now);
	}
	if (act->switch_trainee && l->stage == LOGIN_IN) {
		send_logout(a, now);
	}
	log_stage(l, was);
}

/* T: the patient to the next position (after the one it lies in or
 * turns to); N: the assistant's hand on the case's next site, off after
 * the last. */
static void command_patient(struct app *a, const struct ui_actions *act,
			    const struct endosim_state *st, uint64_t now)
{
	const struct endosim_patient_state *p = st ? &st->patient : NULL;
	const struct model *m = a->colon.model;
	int next;

	if (!a->rig || !p) {
		return;
	}
	if (act->turn_patient) {
		rigctl_patient(a->rig, RIGCTL_PATIENT_TURN,
			       names_position((p->position + 1) %
					      (ENDOSIM_POSITION_PRONE + 1)),
			       now);
	}
	if (!act->next_hand) {
		return;
	}
	next = p->hand_site + 1;
	if (m && next < m->sites) {
		rigctl_patient(a->rig, RIGCTL_PATIENT_PRESS,
			       m->site[next].name, now);
	} else {
		rigctl_patient(a->rig, RIGCTL_PATIENT_RELEASE, NULL, now);
	}
}

/* The patient's voice at T_S (the live or the replay's clock): the clip
 * due now, played and logged. */
static void speak(struct app *a, const struct endosim_state *st, double t_s)
{
	enum voice_clip c;

	if (!st) {
		return;
	}
	c = voice_step(&a->voice, &st->patient, t_s);
	if (c == VOICE_NONE) {
		return;
	}
	sound_play(a->sound, c);
	log_info("voice: %s, pain %.1f, at %.3f s, %.3f s of sound",
		 voice_clip_name(c), st->patient.pain, t_s,
		 sound_time_s(a->sound));
}

/* The replay's state at its clock, run on since the last frame (by a
 * fixed step per frame in a headless run, so that it is reproducible);
 * its strip chart, from the records. */
static const struct endosim_state *update_replay(struct app *a, uint64_t now)
{
	struct replay *r = a->replay;
	double dt = a->opt.frames > 0 ? HEADLESS_FRAME_S :
			fmin((double)(now - a->replay_ns) / ENDOSIM_NS_PER_S,
			     REPLAY_MAX_STEP_S);
	double t;

	if (a->frame > 0) {
		replay_advance(r, dt);
	}
	a->replay_ns = now;
	t = replay_time(r);
	hud_chart_clear(a->hud);
	for (double c = fmax(0, t - HUD_CHART_S); c <= t; c += CHART_STEP_S) {
		struct endosim_state past;

		replay_record_at(r, c, &past);
		hud_record(a->hud, &past, c);
	}
	a->hr = (struct hud_replay){
		.trainee = replay_trainee(r), .case_name = replay_case(r),
		.t_s = t, .duration_s = replay_duration(r),
		.speed = replay_speed(r), .paused = replay_paused(r),
		.records = replay_records(r),
	};
	return replay_state(r);
}

static void fill_replay_info(const struct app *a, const struct endosim_state *st,
			     struct hud_info *in)
{
	*in = (struct hud_info){
		.link = LINK_LIVE,
		.link_problem = "",
		.st = st,
		.loop_threshold_m = replay_loop_threshold_m(a->replay),
		.m = a->colon.model,
		.rig_problem = "",
		.rig_said = "Space pause, + - speed, Left Right seek; H: keys",
		.fps = timing_fps(a->timing),
		.triangles = a->triangles,
		.help = a->help,
		.compact = a->opt.view == HUD_VIEW_BOTH,
		.replay = &a->hr,
	};
	replay_patient_limits(a->replay, &in->relief_pa,
			      &in->strength_n_per_m);
}

static void fill_info(const struct app *a, const struct endosim_state *st,
		      uint64_t now, struct hud_info *in)
{
	if (a->replay) {
		fill_replay_info(a, st, in);
		return;
	}
	*in = (struct hud_info){
		.link = a->status,
		.link_problem = link_problem(a->link),
		.stale_s = link_stale_s(a->link, now),
		.st = st,
		.loop_threshold_m = link_loop_threshold_m(a->link),
		.m = a->colon.model,
		.loading = a->loading,
		.rig_problem = rigctl_problem(a->rig),
		.rig_said = rigctl_said(a->rig),
		.driving = a->hand.engaged && rigctl_driving(a->rig),
		.fps = timing_fps(a->timing),
		.triangles = a->triangles,
		.age_ms = st && a->status == LINK_LIVE
				  ? (double)((int64_t)mono_ns() -
					     (int64_t)st->publish_ns) /
					    ENDOSIM_NS_PER_MS
				  : 0,
		.help = a->help,
		.compact = a->opt.view == HUD_VIEW_BOTH,
		.trainee = a->login.stage == LOGIN_IN ? a->login.trainee : "",
	};
	link_patient_limits(a->link, &in->relief_pa, &in->strength_n_per_m);
}

/* The panel's line about the voice. */
static const char *voice_line(struct app *a)
{
	if (a->sound) {
		snprintf(a->voice_line, sizeof(a->voice_line), "voice %s",
			 a->opt.mute ? "muted (U: on)" : "on (U: mute)");
	}
	return a->voice_line;
}

/* --pass-times: pass K of this frame is drawn; finishes it and counts
 * the time since the last pass finished. */
static void pass_done(struct app *a, enum timing_kind k)
{
	uint64_t now;

	if (!a->opt.pass_times) {
		return;
	}
	glFinish();
	now = mono_ns();
	if (a->frame >= a->timed_from && !a->loading && a->pass_ns) {
		timing_add(a->timing, k, (double)(now - a->pass_ns) /
					 ENDOSIM_NS_PER_MS);
	}
	a->pass_ns = now;
}

static void draw_views(struct app *a, const struct hud_layout *lay,
		       const struct endosim_state *st, bool current,
		       double t_s)
{
	const struct colon_set *c = &a->colon;
	struct endo_camera cam;
	struct endo_stats es;

	a->triangles = 0;
	a->overview_shown = c->model && lay->overview.w;
	a->endo_shown = false;
	if (!c->model) {
		return;
	}
	if (lay->endo.w && current) {
		double lens = lensfx_image_factor(&st->patient);
		struct endo_rect in = imagescale_begin(a->scale, lay->endo,
						       a->image_scale * lens);

		endo_camera(c->model, st, &cam);
		endo_draw(a->endo, c->model, c->lod, c->gpu, &cam, in, &es);
		a->endo_shown = true;
		a->cam = cam;
		a->endo_rect = lay->endo;
		pass_done(a, TIMING_PASS_IMAGE);
		lensfx_draw(a->lensfx, &st->patient, in, lens, t_s);
		pass_done(a, TIMING_PASS_LENS);
		imagescale_end(a->scale, lay->endo);
		pass_done(a, TIMING_PASS_SCALE);
		a->triangles += es.triangles;
	}
	if (lay->overview.w) {
		struct endo_rect in = imagescale_begin(a->overscale,
						       lay->overview, 1);

		a->triangles += overview_draw(a->overview, c->model, c->lod,
					      c->gpu, current ? st : NULL,
					      &a->orbit, in);
		imagescale_end(a->overscale, lay->overview);
		pass_done(a, TIMING_PASS_OVERVIEW);
	}
	if (a->triangles > a->triangles_max) {
		a->triangles_max = a->triangles;
	}
}

static void render(struct app *a, const struct endosim_state *st,
		   bool current, uint64_t now)
{
	double t_s = a->replay ? replay_time(a->replay) :
				 (double)now / ENDOSIM_NS_PER_S;
	struct hud_layout lay;
	struct hud_info in;
	int w, h;

	ui_framebuffer_size(a->ui, &w, &h);
	pass_done(a, TIMING_PASS_UPDATE); /* since the last swap; GL idle */
	glViewport(0, 0, w, h);
	glClearColor(0, 0, 0, 1);
	glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); /* depth if any */
	if (a->opt.view == VIEWOPTS_VIEW_EMPTY || w <= 0 || h <= 0) {
		return; /* the benchmark's empty frame, or a minimised window */
	}
	hud_layout((enum hud_view)a->opt.view, w, h, &lay);
	draw_views(a, &lay, st, current, t_s);
	fill_info(a, st, now, &in);
	in.compact |= lay.panel.w < COMPACT_PANEL_PX;
	in.voice = voice_line(a);
	draw2d_begin(a->d2d, w, h);
	if (lay.overview.w && a->colon.model) {
		overview_labels(a->overview, a->colon.model, a->d2d, h);
	}
	hud_draw(a->hud, a->d2d, &lay, &in, w, h, t_s);
	if (a->map_shown) {
		mapview_draw(a->mapview, a->d2d, w, h,
			     a->status == LINK_LIVE ? st : NULL);
	}
	loginview_draw(a->d2d, &a->login, w, h, (double)now /
		       ENDOSIM_NS_PER_S);
	draw2d_end(a->d2d);
	pass_done(a, TIMING_PASS_PANEL);
}

/* After the swap: the frame's time and the age of the state it showed. */
static void account(struct app *a, const struct endosim_state *st,
		    uint64_t swapped)
{
	bool timed = a->frame >= a->timed_from && !a->loading;

	if (timed && a->last_swap_ns) {
		timing_add(a->timing, TIMING_FRAME,
			   (double)(swapped - a->last_swap_ns) /
				   ENDOSIM_NS_PER_MS);
	}
	if (timed && st && a->status == LINK_LIVE &&
	    swapped > st->publish_ns) {
		timing_add(a->timing, TIMING_AGE,
			   (double)(swapped - st->publish_ns) /
				   ENDOSIM_NS_PER_MS);
	}
	a->last_swap_ns = swapped;
	a->frame++;
}

/* The P key: the frame as endoview-DATE-TIME.png in the current folder
 * (endoview-DATE-TIME-2.png and on for more in the same second: none
 * written over). */
static void capture(int w, int h)
{
	char stamp[32], name[64];
	time_t t = time(NULL);
	struct tm tm;

	localtime_r(&t, &tm);
	strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &tm);
	snprintf(name, sizeof(name), "endoview-%s.png", stamp);
	for (int k = 2; access(name, F_OK) == 0 && k < 1000; k++) {
		snprintf(name, sizeof(name), "endoview-%s-%d.png", stamp, k);
	}
	if (shot_write(name, w, h)) {
		log_err("%s: cannot write the picture", name);
	} else {
		log_info("saved %s", name);
	}
}

static int frame(struct app *a)
{
	const struct endosim_state *st;
	struct input_controls c;
	struct ui_actions acts;
	uint64_t now = mono_ns();
	struct hud_layout lay;
	bool current;
	int w, h, err = 0;

	ui_set_typing(a->ui, a->login.stage == LOGIN_ASK);
	glfwPollEvents();
	ui_framebuffer_size(a->ui, &w, &h);
	hud_layout((enum hud_view)(a->opt.view % HUD_VIEWS), w, h, &lay);
	ui_frame(a->ui, &lay, &c, &acts, &a->orbit);
	act(a, &acts, now);
	if (a->replay) {
		st = update_replay(a, now);
	} else {
		update_link(a, now);
		update_login(a, &acts, now);
		st = link_state(a->link);
		drive(a, &c, st, now);
		command_patient(a, &acts, st, now);
	}
	mapview_update(a->mapview, a->map_shown, now);
	speak(a, st, a->replay ? replay_time(a->replay) :
				 (double)now / ENDOSIM_NS_PER_S);
	current = colon_current(a, st);
	if (st && a->status == LINK_LIVE && !a->replay) {
		hud_record(a->hud, st, (double)now / ENDOSIM_NS_PER_S);
	}
	render(a, st, current, now);
	if (gfx_check("frame")) {
		err = -EIO;
	}
	if (a->opt.screenshot && a->frame + 1 == a->opt.frames &&
	    shot_write(a->opt.screenshot, w, h)) {
		log_err("%s: cannot write the screenshot", a->opt.screenshot);
		err = -EIO;
	}
	if (acts.capture) {
		capture(w, h);
	}
	glfwSwapBuffers(a->window);
	pass_done(a, TIMING_PASS_SWAP);
	a->shown = st;
	account(a, st, mono_ns());
	return acts.quit ? 1 : err;
}

/* ------------------------------------------------------------ main */

static const char *status_name(const struct app *a)
{
	enum link_status s = a->status;

	return a->replay ? "replay" : s == LINK_LIVE ? "live" :
	       s == LINK_STALE ? "stale" : "none";
}

/* The closing lines: the figures, and where each view lies in the image
 * (top-left origin, as in the PNG). */
static void report(const struct app *a)
{
	struct viewstats s = {
		.frames = a->frame,
		.seconds = (double)(a->last_swap_ns - a->start_ns) /
			   ENDOSIM_NS_PER_S,
		.timing = a->timing,
		.triangles = a->triangles,
		.triangles_max = a->triangles_max,
		.gl_errors = gfx_errors_total(),
		.daemon = status_name(a),
		.colon = a->colon.model ? a->colon.model->name : "none",
		.view = (enum hud_view)(a->opt.view % HUD_VIEWS),
		.map_shown = a->map_shown,
	};

	ui_framebuffer_size(a->ui, &s.width, &s.height);
	viewstats_print(stdout, &s);
}

/* "endo: WHAT at X,Y": where the endoscopic view put point AT, in the
 * image's pixels (top-left origin, as in the PNG), if in front of it. */
static void report_point(const struct app *a, int fb_h, const char *what,
			 const double at[3])
{
	double px[2];

	if (endo_project(&a->cam, a->endo_rect, at, px)) {
		printf("endo: %s at %.1f,%.1f\n", what, px[0], fb_h - px[1]);
	}
}

/* Where the endoscopic view drew what the tools left: the bleeding
 * point, the last clip, each cut polyp lying in the lumen. */
static void report_left(const struct app *a, int fb_h)
{
	const struct toolview *tv = &a->cam.tool;
	const struct endosim_tool_state *t = &a->shown->tool;
	char what[32];

	if (t->bleeding > 0) {
		report_point(a, fb_h, "bleeding", t->bleed_at);
	}
	if (t->clips > 0) {
		report_point(a, fb_h, "clip", t->clip_at);
	}
	for (int k = 0; k < ENDOSIM_POLYPS; k++) {
		double at[3];

		if (!(tv->lying >> k & 1u)) {
			continue;
		}
		at[0] = tv->lie[k][0];
		at[1] = tv->lie[k][1];
		at[2] = tv->lie[k][2];
		snprintf(what, sizeof(what), "polyp %d lying", k);
		report_point(a, fb_h, what, at);
	}
}

/* What the panel said (and how much had no room, where its text
 * ended), where the endoscopic view drew what the tools left and the
 * overview the scope and the colon, in the last frame (hud_said(),
 * report_left(), overview_print()). */
static void report_drawn(const struct app *a)
{
	const char *said;
	int w, h;

	char login[512];

	for (int i = 0; (said = hud_said(a->hud, i)); i++) {
		printf("hud: %s\n", said);
	}
	printf("panel: hidden=%d end_px=%.0f\n", hud_hidden(a->hud),
	       hud_end_px(a->hud));
	if (!a->replay) {
		login_said(&a->login, login, sizeof(login));
		printf("login: %s\n", login);
	}
	if (a->map_shown) {
		printf("map: %s\n", mapview_said(a->mapview));
	}
	ui_framebuffer_size(a->ui, &w, &h);
	if (a->endo_shown) {
		report_left(a, h);
	}
	if (a->overview_shown) {
		overview_print(a->overview, a->colon.model, a->shown, h,
			       stdout);
	}
}

/* The replay's clock, and the state the last frame showed. */
static void report_state(const struct app *a)
{
	if (a->replay) {
		printf("endoview: replay t=%.3f duration=%.3f speed=%g "
		       "paused=%d records=%zu bytes_ignored=%zu\n",
		       replay_time(a->replay), replay_duration(a->replay),
		       replay_speed(a->replay), replay_paused(a->replay),
		       replay_records(a->replay),
		       replay_bytes_ignored(a->replay));
	}
	if (a->opt.print_state && a->shown) {
		state_text_print(stdout, "state: ", a->shown);
		report_drawn(a);
	}
}

/*
 * --max-fps: waits until the frame's share of a second since the last
 * one began has passed; a late frame starts the count afresh (no burst of
 * frames to catch up).
 */
static void pace(struct app *a)
{
	uint64_t period, now = mono_ns();
	struct timespec ts;

	if (a->opt.max_fps <= 0) {
		return;
	}
	period = (uint64_t)((double)ENDOSIM_NS_PER_S / a->opt.max_fps);
	if (a->frame_due_ns <= now) {
		a->frame_due_ns = now + period;
		return;
	}
	ts.tv_sec = (time_t)(a->frame_due_ns / ENDOSIM_NS_PER_S);
	ts.tv_nsec = (long)(a->frame_due_ns % ENDOSIM_NS_PER_S);
	while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) ==
	       EINTR) {
	}
	a->frame_due_ns += period;
}

static int run(struct app *a)
{
	int r = 0;

	a->start_ns = mono_ns();
	a->orbit.zoom = 1;
	a->timed_from = WARM_UP_FRAMES;
	if (a->replay && build_colon(a, replay_scene(a->replay))) {
		return -EINVAL;
	}
	while (r == 0 && (a->opt.frames < 0 || a->frame < a->opt.frames)) {
		pace(a);
		r = frame(a);
	}
	if (a->opt.frames > 0 || a->opt.stats) {
		report(a);
	}
	report_state(a);
	if (a->logged_in_here && a->login.stage == LOGIN_IN) {
		char words[256];

		if (rigctl_logout(a->rig, mono_ns(), words, sizeof(words))) {
			log_info("logout at exit refused: %s", words);
		} else {
			log_info("login: %s logged out as endoview quits",
				 a->login.trainee);
		}
	}
	return r < 0 ? r : 0;
}

static void cleanup(struct app *a)
{
	sound_destroy(a->sound);
	colon_free(&a->colon);
	ui_destroy(a->ui);
	timing_destroy(a->timing);
	hud_destroy(a->hud);
	mapview_destroy(a->mapview);
	overview_destroy(a->overview);
	lensfx_destroy(a->lensfx);
	imagescale_destroy(a->scale);
	imagescale_destroy(a->overscale);
	endo_destroy(a->endo);
	draw2d_destroy(a->d2d);
	font_destroy(a->font);
	if (a->window) {
		glfwDestroyWindow(a->window);
		glfwTerminate();
	}
	rigctl_destroy(a->rig);
	link_destroy(a->link);
	replay_destroy(a->replay);
}

/* The clips' folder: --voice, else voice/ beside the program (the
 * build's), else the installed one. */
static void voice_dir(const struct viewopts *o, char *buf, size_t size)
{
	char exe[PATH_MAX];
	ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);

	if (o->voice) {
		snprintf(buf, size, "%s", o->voice);
		return;
	}
	if (n > 0) {
		exe[n] = '\0';
		snprintf(buf, size, "%s/voice", dirname(exe));
		if (access(buf, R_OK) == 0) {
			return;
		}
	}
	snprintf(buf, size, "%s", ENDOVIEW_VOICE_DIR);
}

/* The voice, and the audio device it sounds through: without one, one
 * line says why and the patient is silent. */
static void open_voice(struct app *a)
{
	const char *names[VOICE_CLIPS];
	char dir[PATH_MAX], err[512];

	voice_init(&a->voice);
	voice_set_muted(&a->voice, a->opt.mute);
	for (int k = 0; k < VOICE_CLIPS; k++) {
		names[k] = voice_clip_name((enum voice_clip)k);
	}
	voice_dir(&a->opt, dir, sizeof(dir));
	a->sound = sound_create(dir, names, VOICE_CLIPS, err, sizeof(err));
	if (!a->sound) {
		log_warn("no sound (%s): the patient is silent", err);
		snprintf(a->voice_line, sizeof(a->voice_line), "no sound: %.*s",
			 (int)sizeof(a->voice_line) - 12, err);
	}
}

static int open_replay(struct app *a)
{
	char err[512];

	a->replay = replay_open(a->opt.replay, err, sizeof(err));
	if (!a->replay) {
		log_err("%s", err);
		return -1;
	}
	replay_seek(a->replay, a->opt.seek_s);
	replay_set_speed(a->replay, a->opt.speed);
	replay_set_paused(a->replay, a->opt.paused);
	log_info("replay of %s: %s on %s, %zu records, %.1f s%s", a->opt.replay,
		 replay_trainee(a->replay), replay_case(a->replay),
		 replay_records(a->replay), replay_duration(a->replay),
		 replay_bytes_ignored(a->replay) ? ", its tail cut short" : "");
	return 0;
}

int main(int argc, char **argv)
{
	struct app a = { 0 };
	int r = 1;

	log_init("endoview", LOG_INFO);
	if (viewopts_parse(argc, argv, &a.opt)) {
		viewopts_usage(stderr);
		return 2;
	}
	if (a.opt.replay && open_replay(&a)) {
		goto out;
	}
	login_init(&a.login, a.opt.no_login || a.opt.replay, a.opt.trainee,
		   a.opt.trainee ? getenv("ENDOSIM_PIN") : NULL);
	if (!a.opt.replay) {
		a.link = link_create(a.opt.socket, a.opt.shm_name);
		a.rig = rigctl_create(a.opt.socket);
		if (!a.link || !a.rig) {
			log_err("out of memory");
			goto out;
		}
	}
	a.window = open_window(&a.opt);
	if (!a.window || make_renderers(&a)) {
		goto out;
	}
	if (a.replay) {
		ui_set_replay(a.ui);
	}
	open_voice(&a);
	r = run(&a) ? 1 : 0;
out:
	cleanup(&a);
	return r;
}
