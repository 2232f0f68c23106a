/*
 * viewopts.h - endoview's command line (endoview.c's usage):
 *
 *   endoview [--socket PATH] [--shm-name NAME] [--view endo|overview|both]
 *            [--size WxH] [--screenshot FILE.png] [--frames N]
 *            [--no-vsync] [--max-fps N] [--image-scale S]
 *            [--font FILE.ttf] [--stats] [--pass-times] [--mute]
 *            [--voice DIR] [--trainee NAME | --no-login]
 *            [--print-state] [--replay FILE [--seek S] [--speed X] [--paused]]
 *
 * The main thread, at start-up; no allocation (the strings point into
 * argv).
 */
#ifndef ENDOVIEW_VIEWOPTS_H
#define ENDOVIEW_VIEWOPTS_H

#include <stdbool.h>
#include <stdio.h>

#include "viewer/hud.h"

/* where the installed voice's clips are (the Makefile's VOICEDIR) */
#ifndef ENDOVIEW_VOICE_DIR
#define ENDOVIEW_VOICE_DIR "/usr/local/share/endosim/voice"
#endif

/* --view empty: clear and swap only, the benchmark's */
enum { VIEWOPTS_VIEW_EMPTY = HUD_VIEWS };

struct viewopts {
	const char *socket, *shm_name, *screenshot, *font, *replay;
	const char *voice;      /* the clips' folder; NULL: the default */
	const char *trainee;    /* logs in to train at start (login.h);
				   NULL: the login screen asks */
	int view, width, height; /* enum hud_view or VIEWOPTS_VIEW_EMPTY;
				    px */
	long frames;            /* -1: until closed */
	double seek_s, speed;
	double max_fps;         /* 0: as fast as vsync lets it */
	double image_scale;     /* 0: by the renderer (imagescale.h) */
	bool vsync, stats, print_state, paused;
	bool pass_times;        /* each pass finished and timed (viewstats.h) */
	bool mute;              /* the patient's voice off at start */
	bool no_login;          /* never ask who is training */
};

/* The usage and every option's line of help into F. */
void viewopts_usage(FILE *f);

/*
 * ARGV into O, the defaults where an option is not given (1280x720, the
 * endoscopic view, vsync, DejaVu Sans, speed 1; with --screenshot 45
 * frames). 0, or -EINVAL for a malformed or unknown option, an
 * argument left over, or --trainee with --no-login. --help prints the usage and --version the version
 * to stdout and exit(0).
 */
int viewopts_parse(int argc, char **argv, struct viewopts *o);

#endif
