/* viewopts.c - see viewopts.h. */
#include "viewer/viewopts.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "proto/client.h"
#include "proto/endosim_shm.h"
#include "proto/version.h"
#include "viewer/font.h"
#include "viewer/imagescale.h"

void viewopts_usage(FILE *f)
{
	fprintf(f,
		"usage: endoview [--socket PATH] [--shm-name NAME]\n"
		"                [--view endo|overview|both] [--size WxH]\n"
		"                [--screenshot FILE.png] [--frames N]\n"
		"                [--no-vsync] [--max-fps N] [--image-scale S]\n"
		"                [--font FILE.ttf] [--mute] [--voice DIR]\n"
		"                [--trainee NAME | --no-login]\n"
		"                [--stats] [--pass-times] [--print-state]\n"
		"                [--replay FILE [--seek S] [--speed X] "
		"[--paused]]\n"
		"  --socket PATH     endosimd's socket directory (or socket);\n"
		"                    default $%s, else %s\n"
		"  --shm-name NAME   its shared memory (default %s)\n"
		"  --view V          endo (default), overview, or both\n"
		"  --size WxH        window size (default 1280x720)\n"
		"  --screenshot F    write the last frame to F (PNG)\n"
		"  --frames N        draw N frames, then exit (default with\n"
		"                    --screenshot: 45)\n"
		"  --no-vsync        draw as fast as possible\n"
		"  --max-fps N       draw N frames a second at most (1 to 1000:\n"
		"                    leaves CPU to the force loop where the\n"
		"                    drawing is done in software)\n"
		"  --image-scale S   draw the endoscopic image at S (0.25 to 1)\n"
		"                    of its size, scaled up (default: 0.5\n"
		"                    where the drawing is done in software,\n"
		"                    else 1)\n"
		"  --font F          a TrueType font for the HUD\n"
		"  --mute            the patient's voice off (the key U\n"
		"                    turns it on and off)\n"
		"  --voice DIR       the voice's clips (default: voice/\n"
		"                    beside endoview, else %s)\n"
		"  --trainee NAME    log NAME in to train at the rig at\n"
		"                    start, the PIN from $ENDOSIM_PIN (else\n"
		"                    the login screen asks for it)\n"
		"  --no-login        never ask who is training (the login\n"
		"                    screen shows where the rig's accounts\n"
		"                    hold a trainee; C logs out)\n"
		"  --stats           print the frame figures at exit\n"
		"  --pass-times      finish each pass of a frame before the\n"
		"                    next and print what each took (slows\n"
		"                    the frame: for finding where it goes)\n"
		"  --print-state     print the last frame's state at exit,\n"
		"                    what its panel said and where its\n"
		"                    overview drew the scope and the colon\n"
		"  --replay FILE     play a recorded session (no daemon)\n"
		"  --seek S          start S seconds into it\n"
		"  --speed X         at X times real time (0.25 to 8)\n"
		"  --paused          start paused\n",
		CLIENT_ENV, CLIENT_DEFAULT_DIR, ENDOSIM_SHM_DEFAULT_NAME,
		ENDOVIEW_VOICE_DIR);
}

static int parse_view(const char *s)
{
	static const char *const names[] = { "endo", "overview", "both",
					     "empty" };

	for (int k = 0; k < 4; k++) {
		if (!strcmp(s, names[k])) {
			return k;
		}
	}
	return -1;
}

static int parse_size(const char *s, int *w, int *h)
{
	if (sscanf(s, "%dx%d", w, h) != 2 || *w < 160 || *h < 120 ||
	    *w > 8192 || *h > 8192) {
		return -EINVAL;
	}
	return 0;
}

static int parse_number(const char *s, double *out)
{
	char *end;

	*out = strtod(s, &end);
	return end == s || *end || !isfinite(*out) || *out < 0 ? -EINVAL : 0;
}

int viewopts_parse(int argc, char **argv, struct viewopts *o)
{
	static const struct option longs[] = {
		{ "socket", required_argument, NULL, 's' },
		{ "shm-name", required_argument, NULL, 'm' },
		{ "view", required_argument, NULL, 'v' },
		{ "size", required_argument, NULL, 'z' },
		{ "screenshot", required_argument, NULL, 'o' },
		{ "frames", required_argument, NULL, 'n' },
		{ "no-vsync", no_argument, NULL, 'V' },
		{ "max-fps", required_argument, NULL, 'F' },
		{ "image-scale", required_argument, NULL, 'I' },
		{ "font", required_argument, NULL, 'f' },
		{ "stats", no_argument, NULL, 'S' },
		{ "pass-times", no_argument, NULL, 'T' },
		{ "print-state", no_argument, NULL, 'P' },
		{ "replay", required_argument, NULL, 'r' },
		{ "seek", required_argument, NULL, 'k' },
		{ "speed", required_argument, NULL, 'x' },
		{ "paused", no_argument, NULL, 'p' },
		{ "mute", no_argument, NULL, 'u' },
		{ "voice", required_argument, NULL, 'C' },
		{ "trainee", required_argument, NULL, 't' },
		{ "no-login", no_argument, NULL, 'L' },
		{ "help", no_argument, NULL, 'h' },
		{ "version", no_argument, NULL, 'R' },
		{ 0 },
	};
	int c;

	*o = (struct viewopts){ .view = HUD_VIEW_ENDO, .width = 1280,
				.height = 720, .vsync = true, .frames = -1,
				.font = FONT_DEFAULT_PATH, .speed = 1 };
	while ((c = getopt_long(argc, argv, "", longs, NULL)) != -1) {
		switch (c) {
		case 's':
			o->socket = optarg;
			break;
		case 'm':
			o->shm_name = optarg;
			break;
		case 'v':
			o->view = parse_view(optarg);
			if (o->view < 0) {
				return -EINVAL;
			}
			break;
		case 'z':
			if (parse_size(optarg, &o->width, &o->height)) {
				return -EINVAL;
			}
			break;
		case 'o':
			o->screenshot = optarg;
			break;
		case 'n':
			o->frames = strtol(optarg, NULL, 10);
			if (o->frames < 1) {
				return -EINVAL;
			}
			break;
		case 'V':
			o->vsync = false;
			break;
		case 'I':
			if (parse_number(optarg, &o->image_scale) ||
			    o->image_scale < IMAGESCALE_MIN ||
			    o->image_scale > 1) {
				return -EINVAL;
			}
			break;
		case 'F':
			if (parse_number(optarg, &o->max_fps) ||
			    o->max_fps < 1 || o->max_fps > 1000) {
				return -EINVAL;
			}
			break;
		case 'f':
			o->font = optarg;
			break;
		case 'S':
			o->stats = true;
			break;
		case 'T':
			o->pass_times = true;
			break;
		case 'P':
			o->print_state = true;
			break;
		case 'r':
			o->replay = optarg;
			break;
		case 'k':
		case 'x':
			if (parse_number(optarg, c == 'k' ? &o->seek_s :
							    &o->speed)) {
				return -EINVAL;
			}
			break;
		case 'p':
			o->paused = true;
			break;
		case 'u':
			o->mute = true;
			break;
		case 'C':
			o->voice = optarg;
			break;
		case 't':
			o->trainee = optarg;
			break;
		case 'L':
			o->no_login = true;
			break;
		case 'h':
			viewopts_usage(stdout);
			exit(0);
		case 'R':
			printf("endoview %s\n", ENDOSIM_VERSION);
			exit(0);
		default:
			return -EINVAL;
		}
	}
	if (optind != argc || (o->trainee && o->no_login)) {
		return -EINVAL;
	}
	if (o->screenshot && o->frames < 0) {
		o->frames = 45;
	}
	return 0;
}
