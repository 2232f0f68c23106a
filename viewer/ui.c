/* ui.c - see ui.h. */
#include "viewer/ui.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum drag_on { DRAG_NONE, DRAG_ENDO, DRAG_OVERVIEW, DRAG_TIMELINE };

struct ui {
	GLFWwindow *window;
	struct ui_actions pending; /* from the key callback */
	double scroll;             /* steps since the last frame */
	int button;                /* the dragging button, -1: none */
	enum drag_on on;
	double from_x, from_y;     /* framebuffer pixels, top-left origin */
	double last_x, last_y;
	unsigned char pad[GLFW_GAMEPAD_BUTTON_LAST + 1];
	bool replay;
	bool typing;               /* into the login form */
	/* the window as its events last said (ui.h) */
	int win_w, win_h;          /* screen coordinates */
	int fb_w, fb_h;            /* framebuffer pixels */
	double cursor_x, cursor_y; /* screen coordinates, top-left origin */
};

/* The one-off action KEY stands for, or NULL. */
static bool *action_of(struct ui_actions *a, int key)
{
	switch (key) {
	case GLFW_KEY_E:
		return &a->command[RIGCTL_ENABLE];
	case GLFW_KEY_X:
		return &a->command[RIGCTL_DISABLE];
	case GLFW_KEY_SPACE:
		return &a->command[RIGCTL_ESTOP];
	case GLFW_KEY_R:
		return &a->command[RIGCTL_RESET];
	case GLFW_KEY_G:
		return &a->command[RIGCTL_GUIDE_TAKEOVER];
	case GLFW_KEY_F:
		return &a->command[RIGCTL_GUIDE_RESUME];
	case GLFW_KEY_B:
		return &a->command[RIGCTL_GUIDE_RESET];
	case GLFW_KEY_V:
	case GLFW_KEY_TAB:
		return &a->next_view;
	case GLFW_KEY_H:
	case GLFW_KEY_F1:
		return &a->toggle_help;
	case GLFW_KEY_O:
		return &a->reset_orbit;
	case GLFW_KEY_P:
		return &a->capture;
	case GLFW_KEY_M:
		return &a->toggle_map;
	case GLFW_KEY_T:
		return &a->turn_patient;
	case GLFW_KEY_U:
		return &a->toggle_mute;
	case GLFW_KEY_Z:
		return &a->hands_off;
	case GLFW_KEY_N:
		return &a->next_hand;
	case GLFW_KEY_C:
		return &a->switch_trainee;
	case GLFW_KEY_Q:
	case GLFW_KEY_ESCAPE:
		return &a->quit;
	default:
		return NULL;
	}
}

/* A replay's key; false when KEY is not one. Seeking repeats. */
static bool replay_key(struct ui_actions *a, int key, int action, int mods)
{
	double by = mods & GLFW_MOD_SHIFT ? UI_SEEK_LONG_S : UI_SEEK_S;
	bool press = action == GLFW_PRESS;

	switch (key) {
	case GLFW_KEY_SPACE:
		a->toggle_pause |= press;
		return true;
	case GLFW_KEY_EQUAL:
	case GLFW_KEY_KP_ADD:
	case GLFW_KEY_RIGHT_BRACKET:
		a->speed_steps += press;
		return true;
	case GLFW_KEY_MINUS:
	case GLFW_KEY_KP_SUBTRACT:
	case GLFW_KEY_LEFT_BRACKET:
		a->speed_steps -= press;
		return true;
	case GLFW_KEY_LEFT:
	case GLFW_KEY_RIGHT:
		a->seek_by_s += key == GLFW_KEY_LEFT ? -by : by;
		return true;
	case GLFW_KEY_HOME:
		a->seek_home |= press;
		return true;
	case GLFW_KEY_END:
		a->seek_end |= press;
		return true;
	case GLFW_KEY_E:
	case GLFW_KEY_X:
	case GLFW_KEY_R:
	case GLFW_KEY_T:
	case GLFW_KEY_N:
		return true; /* no rig, no patient to command */
	default:
		return false;
	}
}

/* C (a code point, or UI_TYPED_KEY + a form's key) typed. */
static void typed(struct ui *u, uint32_t c)
{
	if (u->pending.n_typed < UI_TYPED_MAX) {
		u->pending.typed[u->pending.n_typed++] = c;
	}
}

/* KEY pressed (or repeated) while typing into the login form. */
static void form_key(struct ui *u, int key, int action)
{
	switch (key) {
	case GLFW_KEY_BACKSPACE:
		typed(u, UI_TYPED_KEY + LOGIN_BACKSPACE);
		break;
	case GLFW_KEY_TAB:
		typed(u, UI_TYPED_KEY + LOGIN_TAB);
		break;
	case GLFW_KEY_ENTER:
	case GLFW_KEY_KP_ENTER:
		typed(u, UI_TYPED_KEY + LOGIN_ENTER);
		break;
	case GLFW_KEY_ESCAPE:
		typed(u, UI_TYPED_KEY + LOGIN_ESCAPE);
		break;
	case GLFW_KEY_F1:
		u->pending.toggle_help |= action == GLFW_PRESS;
		break;
	default:
		break; /* a character: on_char()'s */
	}
}

static void on_char(GLFWwindow *w, unsigned int c)
{
	struct ui *u = glfwGetWindowUserPointer(w);

	if (u->typing) {
		typed(u, c);
	}
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
	struct ui *u = glfwGetWindowUserPointer(w);
	bool *what;

	(void)scancode;
	if (action != GLFW_RELEASE && u->typing) {
		form_key(u, key, action);
		return;
	}
	if (action == GLFW_RELEASE ||
	    (u->replay && replay_key(&u->pending, key, action, mods))) {
		return;
	}
	what = action_of(&u->pending, key);
	if (what && action == GLFW_PRESS) {
		*what = true;
	}
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
	struct ui *u = glfwGetWindowUserPointer(w);

	(void)dx;
	u->scroll += dy;
}

static void on_window_size(GLFWwindow *w, int width, int height)
{
	struct ui *u = glfwGetWindowUserPointer(w);

	u->win_w = width;
	u->win_h = height;
}

static void on_framebuffer_size(GLFWwindow *w, int width, int height)
{
	struct ui *u = glfwGetWindowUserPointer(w);

	u->fb_w = width;
	u->fb_h = height;
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
	struct ui *u = glfwGetWindowUserPointer(w);

	u->cursor_x = x;
	u->cursor_y = y;
}

struct ui *ui_create(GLFWwindow *w)
{
	struct ui *u = calloc(1, sizeof(*u));

	if (!u) {
		return NULL;
	}
	u->window = w;
	u->button = -1;
	glfwGetWindowSize(w, &u->win_w, &u->win_h);
	glfwGetFramebufferSize(w, &u->fb_w, &u->fb_h);
	glfwGetCursorPos(w, &u->cursor_x, &u->cursor_y);
	glfwSetWindowUserPointer(w, u);
	glfwSetKeyCallback(w, on_key);
	glfwSetCharCallback(w, on_char);
	glfwSetScrollCallback(w, on_scroll);
	glfwSetWindowSizeCallback(w, on_window_size);
	glfwSetFramebufferSizeCallback(w, on_framebuffer_size);
	glfwSetCursorPosCallback(w, on_cursor);
	return u;
}

void ui_framebuffer_size(const struct ui *u, int *w, int *h)
{
	*w = u->fb_w;
	*h = u->fb_h;
}

void ui_set_replay(struct ui *u)
{
	u->replay = true;
}

void ui_set_typing(struct ui *u, bool typing)
{
	u->typing = typing;
}

void ui_destroy(struct ui *u)
{
	if (!u) {
		return;
	}
	glfwSetKeyCallback(u->window, NULL);
	glfwSetCharCallback(u->window, NULL);
	glfwSetScrollCallback(u->window, NULL);
	glfwSetWindowSizeCallback(u->window, NULL);
	glfwSetFramebufferSizeCallback(u->window, NULL);
	glfwSetCursorPosCallback(u->window, NULL);
	glfwSetWindowUserPointer(u->window, NULL);
	free(u);
}

static bool key(const struct ui *u, int a, int b)
{
	return glfwGetKey(u->window, a) == GLFW_PRESS ||
	       (b >= 0 && glfwGetKey(u->window, b) == GLFW_PRESS);
}

/* +1, -1 or 0 from a pair of keys (each with an alternative). */
static double axis_keys(const struct ui *u, int plus, int plus2, int minus,
			int minus2)
{
	return (key(u, plus, plus2) ? 1.0 : 0.0) -
	       (key(u, minus, minus2) ? 1.0 : 0.0);
}

/* The handle's valves, held on 1, 2, 3 (or the keypad's). */
static const struct {
	int key, keypad;
	uint32_t bit;
} valve_key[3] = {
	{ GLFW_KEY_1, GLFW_KEY_KP_1, ENDOSIM_VALVE_AIR },
	{ GLFW_KEY_2, GLFW_KEY_KP_2, ENDOSIM_VALVE_WATER },
	{ GLFW_KEY_3, GLFW_KEY_KP_3, ENDOSIM_VALVE_SUCTION },
};

static void keyboard(const struct ui *u, struct input_controls *c)
{
	double fast = key(u, GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT) ?
			      INPUT_FAST : 1.0;

	c->rate[ENDOSIM_AXIS_INSERTION] =
		fast * axis_keys(u, GLFW_KEY_UP, GLFW_KEY_W, GLFW_KEY_DOWN,
				 GLFW_KEY_S);
	c->rate[ENDOSIM_AXIS_ROLL] = axis_keys(u, GLFW_KEY_RIGHT, GLFW_KEY_D,
					       GLFW_KEY_LEFT, GLFW_KEY_A);
	c->rate[ENDOSIM_AXIS_WHEEL_UD] = axis_keys(u, GLFW_KEY_I, -1,
						   GLFW_KEY_K, -1);
	c->rate[ENDOSIM_AXIS_WHEEL_LR] = axis_keys(u, GLFW_KEY_L, -1,
						   GLFW_KEY_J, -1);
	for (int k = 0; k < 3; k++) {
		c->valves |= key(u, valve_key[k].key, valve_key[k].keypad) ?
				     valve_key[k].bit : 0;
	}
}

static double stick(float v)
{
	return fabsf(v) < UI_DEAD_ZONE ? 0 : v;
}

static void gamepad(struct ui *u, struct input_controls *c,
		    struct ui_actions *a)
{
	static const int button[RIGCTL_RESET + 1] = { /* the guidance: keys */
		[RIGCTL_ENABLE] = GLFW_GAMEPAD_BUTTON_START,
		[RIGCTL_DISABLE] = GLFW_GAMEPAD_BUTTON_BACK,
		[RIGCTL_ESTOP] = GLFW_GAMEPAD_BUTTON_B,
		[RIGCTL_RESET] = GLFW_GAMEPAD_BUTTON_Y,
	};
	GLFWgamepadstate g;

	if (!glfwJoystickIsGamepad(GLFW_JOYSTICK_1) ||
	    !glfwGetGamepadState(GLFW_JOYSTICK_1, &g)) {
		return;
	}
	const float *ax = g.axes;

	c->rate[ENDOSIM_AXIS_INSERTION] -= stick(ax[GLFW_GAMEPAD_AXIS_LEFT_Y]);
	c->rate[ENDOSIM_AXIS_ROLL] += stick(ax[GLFW_GAMEPAD_AXIS_LEFT_X]);
	c->rate[ENDOSIM_AXIS_WHEEL_UD] -= stick(ax[GLFW_GAMEPAD_AXIS_RIGHT_Y]);
	c->rate[ENDOSIM_AXIS_WHEEL_LR] += stick(ax[GLFW_GAMEPAD_AXIS_RIGHT_X]);
	for (int k = 0; k <= RIGCTL_RESET; k++) {
		bool down = g.buttons[button[k]] == GLFW_PRESS;

		a->command[k] |= down && !u->pad[button[k]];
		u->pad[button[k]] = down;
	}
}

static bool inside(struct endo_rect r, double x, double y, int fb_h)
{
	double gy = fb_h - y;

	return r.w > 0 && x >= r.x && x < r.x + r.w && gy >= r.y &&
	       gy < r.y + r.h;
}

/* The pointer in framebuffer pixels, top-left origin. */
static void pointer(const struct ui *u, double *x, double *y, int *fb_h)
{
	*fb_h = u->fb_h;
	*x = u->cursor_x * (u->win_w > 0 ? (double)u->fb_w / u->win_w : 1);
	*y = u->cursor_y * (u->win_h > 0 ? (double)u->fb_h / u->win_h : 1);
}

static int pressed_button(const struct ui *u)
{
	if (glfwGetMouseButton(u->window, GLFW_MOUSE_BUTTON_LEFT)) {
		return GLFW_MOUSE_BUTTON_LEFT;
	}
	return glfwGetMouseButton(u->window, GLFW_MOUSE_BUTTON_RIGHT) ?
		       GLFW_MOUSE_BUTTON_RIGHT : -1;
}

static void start_drag(struct ui *u, const struct hud_layout *lay,
		       double x, double y, int fb_h)
{
	u->from_x = u->last_x = x;
	u->from_y = u->last_y = y;
	u->on = u->replay && inside(lay->timeline, x, y, fb_h) ?
			DRAG_TIMELINE :
		inside(lay->endo, x, y, fb_h)	  ? DRAG_ENDO :
		inside(lay->overview, x, y, fb_h) ? DRAG_OVERVIEW :
						      DRAG_NONE;
}

static void drag_endo(const struct ui *u, double x, double y,
		      struct input_controls *c)
{
	if (u->button == GLFW_MOUSE_BUTTON_LEFT) {
		c->drag[ENDOSIM_AXIS_WHEEL_UD] = true;
		c->drag_by[ENDOSIM_AXIS_WHEEL_UD] =
			(u->from_y - y) * UI_STEER_RAD_PER_PX;
		c->drag[ENDOSIM_AXIS_WHEEL_LR] = true;
		c->drag_by[ENDOSIM_AXIS_WHEEL_LR] =
			(x - u->from_x) * UI_STEER_RAD_PER_PX;
	} else {
		c->drag[ENDOSIM_AXIS_ROLL] = true;
		c->drag_by[ENDOSIM_AXIS_ROLL] =
			(x - u->from_x) * UI_TWIST_RAD_PER_PX;
	}
}

static void mouse(struct ui *u, const struct hud_layout *lay,
		  struct input_controls *c, struct ui_actions *a,
		  struct overview_orbit *orbit)
{
	int button = pressed_button(u), fb_h;
	double x, y;

	pointer(u, &x, &y, &fb_h);
	if (button >= 0 && u->button < 0) {
		start_drag(u, lay, x, y, fb_h);
	}
	u->button = button;
	if (button >= 0 && u->on == DRAG_ENDO) {
		drag_endo(u, x, y, c);
	} else if (button >= 0 && u->on == DRAG_TIMELINE) {
		a->seek_to = fmax(0, fmin(1, (x - lay->timeline.x) /
					   lay->timeline.w));
	} else if (button >= 0 && u->on == DRAG_OVERVIEW) {
		orbit->yaw_rad += (x - u->last_x) * 0.01;
		orbit->pitch_rad = fmax(-1.5, fmin(1.5, orbit->pitch_rad +
						   (y - u->last_y) * 0.01));
	}
	u->last_x = x;
	u->last_y = y;
	if (u->scroll != 0 && inside(lay->overview, x, y, fb_h)) {
		orbit->zoom = fmax(0.5, fmin(8, orbit->zoom *
					      pow(1.15, u->scroll)));
	} else {
		c->step[ENDOSIM_AXIS_INSERTION] = u->scroll * UI_SCROLL_M;
	}
	u->scroll = 0;
}

void ui_frame(struct ui *u, const struct hud_layout *lay,
	      struct input_controls *c, struct ui_actions *a,
	      struct overview_orbit *orbit)
{
	memset(c, 0, sizeof(*c));
	*a = u->pending;
	memset(&u->pending, 0, sizeof(u->pending));
	a->seek_to = -1;
	if (u->typing) {
		u->scroll = 0; /* the form: nothing drives */
		u->button = -1;
	} else {
		keyboard(u, c);
		gamepad(u, c, a);
		mouse(u, lay, c, a, orbit);
	}
	if (glfwWindowShouldClose(u->window)) {
		a->quit = true;
	}
}
