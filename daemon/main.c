/*
 * main.c - endosimd: the haptics daemon of the endosim colonoscopy
 * simulator. Start-up order, signals, systemd notification and watchdog,
 * and the log lines for what the force loop reports.
 *
 * Start-up: configuration and the case it names (exit 78 on any error,
 * before anything else), the sockets (refusing to run beside another
 * daemon), shared memory, the rig (devices opened and checked), the force
 * loop, the control thread, then READY=1. Motors stay off until an
 * explicit enable.
 */
#include <errno.h>
#include <getopt.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <sysexits.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>

#include "proto/names.h"
#include "proto/version.h"
#include "conf/cases.h"
#include "conf/config.h"
#include "control/control.h"
#include "loop/faults.h"
#include "rig/hand.h"
#include "base/log.h"
#include "loop/loop.h"
#include "base/mono.h"
#include "loop/publish.h"
#include "recorder/recorder.h"
#include "rig/rig.h"
#include "rig/rig_drives.h"
#include "rig/rig_sim.h"
#include "rig/scenario.h"
#include "session/centre.h"

#define TICK_MS 50

struct options {
	const char *config_path;
	bool config_explicit;
	const char *scenario_path;
	bool check_config;
	bool print_config;
};

struct daemon {
	struct config cfg;
	uint64_t start_ns;
	struct hand *hand;
	struct control *control;
	struct publish *pub;
	struct rig *rig;
	struct loop *loop;
	struct recorder *recorder;
};

static void usage(FILE *out)
{
	fprintf(out,
		"usage: endosimd [options]\n"
		"  -c, --config FILE     configuration (default %s)\n"
		"      --check-config    validate the configuration and exit\n"
		"      --print-config    print the effective configuration and exit\n"
		"      --socket-dir DIR  override [socket] directory\n"
		"      --shm-name NAME   override [shm] name (e.g. /endosim-test)\n"
		"      --session-dir DIR override [session] directory\n"
		"      --set KEY=VALUE   override any key, e.g. --set loop.rate_hz=500\n"
		"      --scenario FILE   simulated hand follows this scenario\n"
		"  -V, --version         print the version and exit\n"
		"  -h, --help            this help\n",
		CONFIG_DEFAULT_PATH);
}

/* Applies one override "KEY=VALUE" (or KEY with VALUE apart). */
static int override(struct config *cfg, const char *key, const char *value)
{
	char err[256];

	if (config_set(cfg, key, value, false, err, sizeof(err))) {
		fprintf(stderr, "endosimd: command line: %s\n", err);
		return -EINVAL;
	}
	return 0;
}

static int override_pair(struct config *cfg, const char *pair)
{
	char key[128];
	const char *eq = strchr(pair, '=');

	if (!eq || (size_t)(eq - pair) >= sizeof(key)) {
		fprintf(stderr, "endosimd: --set %s: expected KEY=VALUE\n",
			pair);
		return -EINVAL;
	}
	memcpy(key, pair, (size_t)(eq - pair));
	key[eq - pair] = '\0';
	return override(cfg, key, eq + 1);
}

enum {
	OPT_CHECK = 256,
	OPT_PRINT,
	OPT_SOCKDIR,
	OPT_SHM,
	OPT_SET,
	OPT_SCN,
	OPT_SESSDIR,
};

static const struct option long_opts[] = {
	{ "config", required_argument, NULL, 'c' },
	{ "check-config", no_argument, NULL, OPT_CHECK },
	{ "print-config", no_argument, NULL, OPT_PRINT },
	{ "socket-dir", required_argument, NULL, OPT_SOCKDIR },
	{ "shm-name", required_argument, NULL, OPT_SHM },
	{ "session-dir", required_argument, NULL, OPT_SESSDIR },
	{ "set", required_argument, NULL, OPT_SET },
	{ "scenario", required_argument, NULL, OPT_SCN },
	{ "version", no_argument, NULL, 'V' },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

/* First pass: the options that say which file to read and what to do. */
static int parse_options(int argc, char **argv, struct options *opt)
{
	int c;

	*opt = (struct options){ .config_path = CONFIG_DEFAULT_PATH };
	while ((c = getopt_long(argc, argv, "c:Vh", long_opts, NULL)) != -1) {
		switch (c) {
		case 'c':
			opt->config_path = optarg;
			opt->config_explicit = true;
			break;
		case OPT_CHECK:
			opt->check_config = true;
			break;
		case OPT_PRINT:
			opt->print_config = true;
			break;
		case OPT_SCN:
			opt->scenario_path = optarg;
			break;
		case OPT_SOCKDIR:
		case OPT_SHM:
		case OPT_SET:
		case OPT_SESSDIR:
			break;
		case 'V':
			printf("endosimd %s\n", ENDOSIM_VERSION);
			exit(0);
		case 'h':
			usage(stdout);
			exit(0);
		default:
			usage(stderr);
			return -EINVAL;
		}
	}
	if (optind < argc) {
		fprintf(stderr, "endosimd: unexpected argument '%s'\n",
			argv[optind]);
		return -EINVAL;
	}
	return 0;
}

/* Second pass, after the file: command-line overrides win. */
static int apply_overrides(int argc, char **argv, struct config *cfg)
{
	int c, r = 0;

	optind = 1;
	while (!r && (c = getopt_long(argc, argv, "c:Vh", long_opts, NULL)) !=
			     -1) {
		if (c == OPT_SOCKDIR) {
			r = override(cfg, "socket.directory", optarg);
		} else if (c == OPT_SHM) {
			r = override(cfg, "shm.name", optarg);
		} else if (c == OPT_SESSDIR) {
			r = override(cfg, "session.directory", optarg);
		} else if (c == OPT_SET) {
			r = override_pair(cfg, optarg);
		}
	}
	return r;
}

/*
 * Run from a checkout, the shipped cases are not in the compiled-in [case]
 * directory but in cases/ beside the configuration file (config/cases
 * beside config/endosimd.conf): taken from there when the directory was
 * left at its default and the case is not in it.
 */
static void find_case_dir(struct config *cfg, const struct options *opt)
{
	const char *conf = opt->config_path, *slash = strrchr(conf, '/');
	int len = slash ? (int)(slash - conf + 1) : 0;
	char dir[CONFIG_STR], path[2 * CONFIG_STR + 8];

	if (!opt->config_explicit || *cfg->colon.file ||
	    strcmp(cfg->colon.directory, CONFIG_CASE_DIR) ||
	    cases_path(cfg, NULL, path, sizeof(path)) ||
	    access(path, F_OK) == 0) {
		return;
	}
	if (snprintf(dir, sizeof(dir), "%.*scases", len, conf) >=
		    (int)sizeof(dir) ||
	    snprintf(path, sizeof(path), "%s/%s.case", dir, cfg->colon.name) >=
		    (int)sizeof(path) ||
	    access(path, F_OK)) {
		return;
	}
	memcpy(cfg->colon.directory, dir, sizeof(dir));
}

static int load_config(int argc, char **argv, const struct options *opt,
		       struct config *cfg)
{
	char err[512];

	config_defaults(cfg);
	if (opt->config_explicit || access(opt->config_path, F_OK) == 0) {
		if (config_load(cfg, opt->config_path, err, sizeof(err))) {
			fprintf(stderr, "endosimd: %s\n", err);
			return -EINVAL;
		}
	}
	if (apply_overrides(argc, argv, cfg)) {
		return -EINVAL;
	}
	if (config_check_whole(cfg, err, sizeof(err))) {
		fprintf(stderr, "endosimd: %s\n", err);
		return -EINVAL;
	}
	find_case_dir(cfg, opt);
	return 0;
}

/* ------------------------------------------------------------ events */

/* One line per fault; a cause that keeps latching again is rate-limited. */
static void log_fault(const struct daemon *d, const struct loop_event *ev)
{
	static struct log_ratelimit rl[ENDOSIM_FAULT_BITS];
	struct endosim_fault_cause c = {
		.first_ns = ev->stamp_ns, .axis = ev->axis,
		.detail = ev->detail, .value = ev->value, .limit = ev->limit,
	};
	struct log_ratelimit *r = &rl[__builtin_ctz(ev->arg)];
	char text[512];

	if (!r->interval_ns) {
		*r = (struct log_ratelimit)LOG_RATELIMIT_INIT(60, 5);
	}
	faults_format(d->rig, d->start_ns, ev->arg, &c, text, sizeof(text));
	log_ratelimited(r, LOG_ERR, "FAULT %s: torque off on every axis; "
			"'endoctl reset' once the cause is gone", text);
}

/* A missed overrun budget that only warns ([loop] overrun_fault). */
static void log_over_budget(const struct daemon *d,
			    const struct loop_event *ev, double t)
{
	static struct log_ratelimit rl = LOG_RATELIMIT_INIT(60, 3);

	log_ratelimited(&rl, LOG_WARNING, "force loop over its overrun "
			"budget at %.3f s: %u periods skipped within %g s, "
			"budget %d; a warning, not a fault ([loop] "
			"overrun_fault = %s); a rig needs isolated CPUs and a "
			"PREEMPT_RT kernel", t, ev->arg,
			d->cfg.loop.overrun_window_s,
			d->cfg.loop.overrun_budget,
			d->cfg.loop.overrun_fault == CONFIG_OVERRUN_WARN
				? "no" : "auto, every axis simulated");
}

static void log_guide(const struct loop_event *ev, double t)
{
	if (ev->arg == ENDOSIM_GUIDE_FADING && ev->detail) {
		return; /* ending: said once it is off */
	}
	if (ev->arg == ENDOSIM_GUIDE_OFF && ev->detail ==
	    ENDOSIM_GUIDE_END_LOST) {
		log_warn("guide: ended at %.3f s, %.2f s into the "
			    "recording: %s could not follow its reference",
			    t, ev->value, names_axis(ev->axis));
	} else if (ev->arg == ENDOSIM_GUIDE_OFF) {
		log_notice("guide: ended (%s) at %.3f s, %.2f s into the "
			   "recording", names_guide_end(ev->detail), t,
			   ev->value);
	} else if (ev->arg == ENDOSIM_GUIDE_FADING) {
		log_notice("guide: taken over at %.3f s, %.2f s into the "
			   "recording: fading out", t, ev->value);
	} else {
		log_info("guide: %s at %.3f s, %.2f s into the recording",
			 names_guide_phase(ev->arg), t, ev->value);
	}
}

static void log_event(const struct daemon *d, const struct loop_event *ev)
{
	static struct log_ratelimit overrun_rl = LOG_RATELIMIT_INIT(10, 3);
	static const char *const cmd_names[] = {
		[LOOP_CMD_ENABLE] = "enable", [LOOP_CMD_DISABLE] = "disable",
		[LOOP_CMD_ESTOP] = "emergency stop", [LOOP_CMD_RESET] = "reset",
	};
	double t = (double)(ev->stamp_ns - d->start_ns) / ENDOSIM_NS_PER_S;

	switch (ev->code) {
	case LOOP_EV_STATE:
		log_notice("state %s -> %s (%s) at %.3f s",
			   names_state(ev->prev), names_state(ev->arg),
			   ev->cmd && ev->cmd <= LOOP_CMD_RESET ? cmd_names[ev->cmd]
								  : "fault", t);
		break;
	case LOOP_EV_FAULT:
		log_fault(d, ev);
		break;
	case LOOP_EV_OVERRUN:
		log_ratelimited(&overrun_rl, LOG_WARNING,
				"force loop overrun: %u period(s) skipped at "
				"%.3f s", ev->arg, t);
		break;
	case LOOP_EV_SCENARIO_END:
		log_info("scenario ended at %.3f s", t);
		break;
	case LOOP_EV_OVER_BUDGET:
		log_over_budget(d, ev, t);
		break;
	case LOOP_EV_GUIDE:
		log_guide(ev, t);
		break;
	}
}

/* ------------------------------------------------------------ life */

/* Some axis is simulated: the simulated hand has something to push. */
static bool any_simulated(const struct config *cfg)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (config_axis_backend(cfg, a) == CONFIG_DRIVE_SIM) {
			return true;
		}
	}
	return false;
}

/* The rig backend [rig] backend names: the factory of rig.h's backends. */
static struct rig *create_rig(const struct config *cfg, struct hand *hand)
{
	switch (cfg->rig.backend) {
	case CONFIG_BACKEND_SIM:
		return rig_sim_create(cfg, hand);
	case CONFIG_BACKEND_DRIVES:
		return rig_drives_create(cfg, hand);
	}
	return NULL;
}

/* The configured case, built before anything else starts. */
static struct colon *load_colon(const struct config *cfg)
{
	char err[512], path[2 * CONFIG_STR + 8];
	struct colon *c = cases_load(cfg, NULL, err, sizeof(err));

	if (!c) {
		log_err("case: %s", err);
		if (!*cfg->colon.file &&
		    !cases_path(cfg, NULL, path, sizeof(path)) &&
		    access(path, F_OK)) {
			log_err("case: no %s.case in %s: name the directory of "
				"the case files with [case] directory or "
				"--set case.directory=DIR", cfg->colon.name,
				cfg->colon.directory);
		}
		return NULL;
	}
	log_info("case %s: %.2f m, %u triangles in %u segments, %.1f MiB",
		 colon_name(c), centreline_length(colon_centreline(c)),
		 colon_mesh(c)->triangles, colon_mesh(c)->segments,
		 (double)colon_bytes(c) / (1 << 20));
	return c;
}

/* [records] centre, when set, a URL libpq reads and without a password:
 * said and refused at start-up, before the colon is built. */
static bool centre_ok(const struct config *cfg)
{
	char err[512];

	if (cfg->records.centre[0] &&
	    centre_check_url(cfg->records.centre, err, sizeof(err))) {
		log_err("[records] centre: %s", err);
		return false;
	}
	return true;
}

static int start(struct daemon *d, const struct options *opt)
{
	struct scenario *scn = NULL;
	struct colon *colon;
	char err[512];

	if (!centre_ok(&d->cfg)) {
		return EX_CONFIG;
	}
	colon = load_colon(&d->cfg);
	if (!colon) {
		return EX_CONFIG;
	}
	if (opt->scenario_path) {
		scn = scenario_load(opt->scenario_path, err, sizeof(err));
		if (!scn) {
			log_err("%s", err);
			colon_destroy(colon);
			return EX_CONFIG;
		}
	}
	d->hand = hand_create(&d->cfg, scn);
	if (!d->hand) {
		scenario_destroy(scn);
		colon_destroy(colon);
		return EX_OSERR;
	}
	d->rig = create_rig(&d->cfg, d->hand);
	if (!d->rig) {
		colon_destroy(colon);
		return EX_SOFTWARE;
	}
	struct control_deps deps = {
		.hand = any_simulated(&d->cfg) ? d->hand : NULL,
		.rig = d->rig,
		.start_ns = d->start_ns,
		.colon = colon,
		.scene_id = 1,
	};

	d->pub = publish_create(d->cfg.shm.name,
				1000000000u / (unsigned)d->cfg.loop.rate_hz,
				d->start_ns);
	if (!d->pub) {
		colon_destroy(colon);
		return EX_UNAVAILABLE;
	}
	d->loop = loop_create(&d->cfg, d->rig, d->pub, colon, deps.scene_id);
	if (!d->loop) {
		colon_destroy(colon);
		return EX_OSERR;
	}
	d->recorder = recorder_create(&d->cfg, d->rig, d->pub, d->start_ns);
	if (!d->recorder) {
		return EX_CANTCREAT;
	}
	loop_set_tap(d->loop, recorder_tap(d->recorder));
	deps.loop = d->loop;
	deps.pub = d->pub;
	deps.recorder = d->recorder;
	d->control = control_create(&d->cfg, &deps);
	if (!d->control) {
		return EX_UNAVAILABLE;
	}
	if (rig_start(d->rig)) {
		return EX_UNAVAILABLE;
	}
	if (loop_start(d->loop) || recorder_run(d->recorder) ||
	    control_start(d->control)) {
		return EX_OSERR;
	}
	return 0;
}

static void stop(struct daemon *d)
{
	if (d->loop) {
		loop_stop(d->loop); /* torque zero, drives disabled */
	}
	control_destroy(d->control);
	recorder_destroy(d->recorder); /* a session's END, after the loop */
	loop_destroy(d->loop);
	publish_destroy(d->pub);
	rig_destroy(d->rig);
	hand_destroy(d->hand);
}

static int open_fds(int *sig_fd, int *tick_fd)
{
	struct itimerspec tick = {
		.it_interval = { .tv_nsec = TICK_MS * 1000000L },
		.it_value = { .tv_nsec = TICK_MS * 1000000L },
	};
	sigset_t set;

	sigemptyset(&set);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGHUP);
	*sig_fd = signalfd(-1, &set, SFD_CLOEXEC);
	*tick_fd = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC);
	if (*sig_fd < 0 || *tick_fd < 0 ||
	    timerfd_settime(*tick_fd, 0, &tick, NULL) < 0) {
		log_err("main: signalfd/timerfd: %m");
		return -errno;
	}
	return 0;
}

/* Pings systemd's watchdog only while the force loop makes progress. */
static void watchdog(struct daemon *d, uint64_t usec, uint64_t *last_beat,
		     uint64_t *last_ping)
{
	uint64_t now = mono_ns();
	uint64_t beat = loop_heartbeat(d->loop);

	if (!usec || now - *last_ping < usec * 1000 / 2) {
		return;
	}
	if (beat != *last_beat) {
		sd_notify(0, "WATCHDOG=1");
		*last_ping = now;
		*last_beat = beat;
	}
}

/*
 * The control thread ended by itself: nobody can command the daemon any
 * more. The force loop latches an internal fault (torque off within a
 * cycle, drives brought down), the state is published for any viewer, and
 * endosimd stops with EX_SOFTWARE so that systemd restarts it.
 */
static int control_died(struct daemon *d)
{
	struct timespec nap = { .tv_nsec = 1000000 };
	struct endosim_state st;
	struct loop_event ev;

	loop_fail(d->loop, ENDOSIM_FAULT_INTERNAL, 1);
	for (int i = 0; i < 200; i++) {
		if (!publish_read(d->pub, &st) &&
		    (st.fault_bits & ENDOSIM_FAULT_INTERNAL)) {
			break;
		}
		nanosleep(&nap, NULL);
	}
	while (loop_pop_event(d->loop, &ev)) {
		log_event(d, &ev);
	}
	log_err("control thread ended: torque off; stopping (exit %d) for "
		"systemd to restart endosimd", EX_SOFTWARE);
	return EX_SOFTWARE;
}

static int run(struct daemon *d)
{
	uint64_t wd_usec = 0, last_beat = 0, last_ping = 0, junk;
	struct signalfd_siginfo si;
	struct loop_event ev;
	struct pollfd pfd[2];
	int sig_fd, tick_fd, r = 0;

	if (open_fds(&sig_fd, &tick_fd)) {
		return EX_OSERR;
	}
	if (sd_watchdog_enabled(0, &wd_usec) <= 0) {
		wd_usec = 0;
	}
	sd_notifyf(0, "READY=1\nSTATUS=running, %s rig, state IDLE",
		   rig_name(d->rig));
	pfd[0] = (struct pollfd){ .fd = sig_fd, .events = POLLIN };
	pfd[1] = (struct pollfd){ .fd = tick_fd, .events = POLLIN };
	for (;;) {
		if (poll(pfd, 2, -1) < 0 && errno != EINTR) {
			log_err("main: poll: %m");
			break;
		}
		if ((pfd[0].revents & POLLIN) &&
		    read(sig_fd, &si, sizeof(si)) == sizeof(si)) {
			if (si.ssi_signo != SIGHUP) {
				log_notice("%s: stopping, torque off",
					   strsignal((int)si.ssi_signo));
				break;
			}
			log_notice("SIGHUP: reload is not supported; restart "
				   "the service to apply a new configuration");
		}
		if ((pfd[1].revents & POLLIN) &&
		    read(tick_fd, &junk, sizeof(junk)) < 0) {
			/* the tick only wakes us */
		}
		while (loop_pop_event(d->loop, &ev)) {
			log_event(d, &ev);
		}
		if (!control_alive(d->control)) {
			r = control_died(d);
			break;
		}
		watchdog(d, wd_usec, &last_beat, &last_ping);
	}
	sd_notify(0, "STOPPING=1");
	close(sig_fd);
	close(tick_fd);
	return r;
}

static void block_signals(void)
{
	sigset_t set;

	sigemptyset(&set);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGHUP);
	sigaddset(&set, SIGPIPE);
	pthread_sigmask(SIG_BLOCK, &set, NULL);
}

int main(int argc, char **argv)
{
	struct daemon d = { 0 };
	struct options opt;
	int r;

	if (parse_options(argc, argv, &opt)) {
		return EX_USAGE;
	}
	if (load_config(argc, argv, &opt, &d.cfg)) {
		return EX_CONFIG;
	}
	if (opt.check_config) {
		struct colon *c;

		log_init("endosimd", d.cfg.log.level);
		c = centre_ok(&d.cfg) ? load_colon(&d.cfg) : NULL;
		if (!c) {
			return EX_CONFIG;
		}
		colon_destroy(c);
		printf("%s: configuration ok\n", opt.config_explicit ||
		       access(opt.config_path, F_OK) == 0 ? opt.config_path
						  : "built-in defaults");
		return 0;
	}
	if (opt.print_config) {
		config_print(&d.cfg, stdout);
		return 0;
	}
	log_init("endosimd", d.cfg.log.level);
	log_info("endosimd %s starting", ENDOSIM_VERSION);
	log_info("overrun budget: %d periods within %g s, missing it is a %s",
		 d.cfg.loop.overrun_budget, d.cfg.loop.overrun_window_s,
		 config_overrun_faults(&d.cfg) ? "fault" : "warning");
	block_signals();
	d.start_ns = mono_ns();
	r = start(&d, &opt);
	if (!r) {
		r = run(&d);
	}
	stop(&d);
	if (!r) {
		log_info("stopped");
	}
	return r;
}
