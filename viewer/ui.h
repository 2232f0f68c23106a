/*
 * ui.h - what the trainee does in endoview's window: GLFW's keyboard,
 * mouse and gamepad turned into the simulated hand's controls (input.h),
 * commands to the daemon (rigctl.h) and the viewer's own actions.
 *
 *   keyboard  Up/W Down/S insert, withdraw (Shift: faster); Left/A
 *             Right/D twist; I K tip up, down; J L tip left, right;
 *             E enable, X disable, Space emergency stop, R reset;
 *             the handle's valves while held: 1 the air/water valve
 *             covered (air), 2 pressed (water onto the lens), 3 suction;
 *             T turn the patient to the next position (left lateral,
 *             supine, right lateral, prone), N the assistant's hand on
 *             the case's next site, then off; U the patient's voice
 *             off and on again (voice.h);
 *             V next view, O overview orbit back, P save a picture,
 *             M the unseen-mucosa map, H help, Q/Esc quit;
 *             C log the trainee out (login.h), another logs in
 *   mouse     on the endoscopic image: drag to steer (the wheels follow
 *             the pointer), right-drag to twist, scroll to insert;
 *             on the overview: drag to turn it, scroll to zoom
 *   gamepad   left stick: insert (up), twist; right stick: steer;
 *             Start enable, Back disable, B emergency stop, Y reset
 *
 * In a replay (ui_set_replay()) the keys drive the replay's clock instead
 * of the rig: Space pause, + - (or ] [) speed, Left Right seek 5 s back
 * or on (Shift: 30 s), Home the start, End the end; a click or a drag on
 * the timeline (struct hud_layout timeline) seeks there. V, O, P, M, U,
 * H, Q and the overview's mouse stay; the hand's controls are still made but a
 * replay does not use them.
 *
 * While the login form is shown (ui_set_typing()) the keyboard types into
 * it instead: each character, and Backspace, Tab, Enter and Esc, in the
 * order typed (struct ui_actions typed); F1 still shows the keys; the
 * hand's controls are all still (the keys, the mouse, the gamepad).
 *
 * Main thread; GLFW's callbacks of the window are ui's.
 */
#ifndef ENDOVIEW_UI_H
#define ENDOVIEW_UI_H

#include <stdbool.h>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "viewer/hud.h"
#include "viewer/input.h"
#include "viewer/login.h"
#include "viewer/overview.h"
#include "viewer/rigctl.h"

#define UI_STEER_RAD_PER_PX 0.008 /* wheel turn per pixel of drag */
#define UI_TWIST_RAD_PER_PX 0.01
#define UI_SCROLL_M 0.005         /* insertion per step of the wheel */
#define UI_DEAD_ZONE 0.15         /* of a stick */

#define UI_SEEK_S 5.0       /* Left, Right in a replay */
#define UI_SEEK_LONG_S 30.0 /* with Shift */

#define UI_TYPED_MAX 64          /* what a frame keeps of the typing */
#define UI_TYPED_KEY 0x110000u   /* + enum login_key: past Unicode */

/* One-off actions this frame. */
struct ui_actions {
	bool command[RIGCTL_COMMANDS]; /* by enum rigctl_command */
	bool next_view, toggle_help, reset_orbit, capture, quit;
	bool toggle_map;     /* the unseen-mucosa overlay (mapview.h) */
	bool turn_patient;   /* T: to the next position */
	bool next_hand;      /* N: the hand on the next site, or off */
	bool toggle_mute;    /* U: the patient's voice off, on */
	bool hands_off;      /* Z: the hand lets go of every axis */
	bool switch_trainee; /* C: the trainee logs out, another logs in */
	/* typed into the login form, in order: code points, or
	   UI_TYPED_KEY + enum login_key; what does not fit is dropped */
	uint32_t typed[UI_TYPED_MAX];
	int n_typed;
	/* a replay's */
	bool toggle_pause, seek_home, seek_end;
	int speed_steps;     /* +1 faster, -1 slower, per key */
	double seek_by_s;    /* Left, Right */
	double seek_to;      /* 0..1 along the timeline; < 0: none */
};

struct ui;

/*
 * Takes the window's key, scroll, cursor and size callbacks. NULL: ENOMEM.
 * The window's size and the pointer are kept as its events say, so that a
 * frame asks the window system nothing: on X11 each glfwGet*Size() and
 * glfwGetCursorPos() is a round trip to the server, which a loaded
 * machine answers late (the frame's tail on a software renderer).
 */
struct ui *ui_create(GLFWwindow *w);

/* The framebuffer's size in pixels, as the last events said. */
void ui_framebuffer_size(const struct ui *u, int *w, int *h);

/* NULL is fine. */
void ui_destroy(struct ui *u);

/* The keys and the timeline drive a replay from now on. */
void ui_set_replay(struct ui *u);

/* The keyboard types into the login form (TYPING), or drives as ever. */
void ui_set_typing(struct ui *u, bool typing);

/*
 * After glfwPollEvents(): the hand's controls C and the actions A of this
 * frame; drags on the overview turn ORBIT. LAY says which view is where.
 */
void ui_frame(struct ui *u, const struct hud_layout *lay,
	      struct input_controls *c, struct ui_actions *a,
	      struct overview_orbit *orbit);

#endif
