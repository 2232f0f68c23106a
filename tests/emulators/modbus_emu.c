/*
 * modbus_emu.c - brushed DC wheel drives on a Modbus line, emulated: a
 * libmodbus slave answering for every modbus axis of an endosimd
 * configuration, with that configuration's slave ids and register maps
 * (read with the daemon's own config.c and regspec.c, turned into values
 * with the rig's regmap.c), each drive turning a motor (emu.h) with the
 * torque written to it plus a scripted hand.
 *
 * Where it listens:
 *   --pty LINK     RTU on a new pseudo-terminal whose other end is symlinked
 *                  at LINK (point [modbus] device there). Killing the
 *                  emulator closes the pty, as pulling a USB-serial adapter
 *                  does; restarting it makes a new one behind LINK.
 *   --tty PATH     RTU on an existing tty (e.g. one end of a socat pair;
 *                  killing the emulator then looks like drives powered off).
 *   --listen PORT  TCP on 127.0.0.1:PORT.
 *   --baud N       delays each reply by the time the request and the reply
 *                  take on an N baud line with [modbus]'s framing, plus
 *                  3.5 characters of silence before each (a pty or loopback
 *                  has no speed of its own); --turnaround S adds the
 *                  drive's own reply time.
 *
 * Control commands (one per line on --control FIFO), SLAVE being an id:
 *   fault SLAVE [CODE] [sticky]  the fault register reads CODE (default 1)
 *                                and the drive stops; fault_reset clears it
 *                                unless sticky (until "clear")
 *   clear SLAVE                  the cause of a sticky fault goes away
 *   exception SLAVE [CODE]       the next request gets exception CODE (4)
 *   mute SLAVE on|off            the drive stops / resumes answering
 *   nan SLAVE on|off             its velocity register (f32) reads NaN
 *   hand SLAVE TORQUE [HZ]       the hand's torque on the motor, N m
 *   move SLAVE RPM               the hand turns the motor at RPM exactly
 *   place SLAVE COUNTS           the motor is put at COUNTS
 *   valve SLAVE air|water|suction on|off
 *                                the drive's input that the configuration
 *                                maps to that valve (valve_air, ...) reads
 *                                pressed / released, by its description
 *                                (an inverted input reads 0 when pressed)
 *   tool SLAVE depth M | opening X | pedal on|off
 *                                the drive's input that the configuration
 *                                maps to the tool's depth (tool_depth, m),
 *                                its handle's opening (tool_opening, 0..1)
 *                                or the pedal reads that, encoded by its
 *                                description
 *   quit
 * --state FILE: one line per drive (slave, axis, enabled, torque applied in
 * N m, position in counts, velocity in counts/s, fault, requests served,
 * the valves its inputs read pressed, the tool's depth, opening, pedal);
 * --trace FILE: every request in hex with what it asked, and the answer.
 */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <modbus.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <termios.h>
#include <unistd.h>

#include "conf/config.h"
#include "base/log.h"
#include "proto/names.h"
#include "rig/regmap.h"
#include "emu.h"

#define MAX_ADU 260
#define STATE_EVERY_S 0.02
#define DEFAULT_FAULT 1
#define WATCHDOG_FAULT 0x8130

struct slave {
	int axis;
	const struct config_modbus_drive *cfg;
	int cpr;
	modbus_mapping_t *map;
	struct emu_motor motor;
	bool enabled;
	double torque_nm;          /* applied */
	double last_request_s;
	uint16_t fault;
	bool sticky;
	bool reset_was_set;
	bool mute;
	bool nan;
	uint32_t valves;           /* enum endosim_valve bits pressed */
	double tool_depth_m;       /* what its tool inputs read */
	double tool_opening;
	bool tool_pedal;
	int exception_next;
	unsigned long requests;
};

struct mbemu {
	struct config cfg;
	struct slave s[ENDOSIM_AXES];
	int n;
	modbus_t *ctx;
	bool tcp;
	int server;                /* TCP: listening socket */
	int fd;                    /* the line, or the TCP client; -1: none */
	int baud;
	double turnaround_s;
	FILE *trace;
	const char *state_path;
	int ctl;
	struct emu_lines lines;
	double last_s, last_state_s;
	bool quit;
};

static volatile sig_atomic_t stop;

/* --- the registers ---------------------------------------------------- */

static uint16_t *words_at(modbus_mapping_t *m, const struct regspec *r)
{
	switch (r->table) {
	case REGSPEC_INPUT:
		return m->tab_input_registers + r->address;
	case REGSPEC_HOLDING:
		return m->tab_registers + r->address;
	default:
		return NULL;
	}
}

static uint8_t *bit_at(modbus_mapping_t *m, const struct regspec *r)
{
	return r->table == REGSPEC_COIL ? m->tab_bits + r->address
				       : m->tab_input_bits + r->address;
}

static void put(struct slave *s, int sig, double value)
{
	const struct regspec *r = &s->cfg->reg[sig];
	uint16_t w[REGSPEC_MAX_WORDS];
	uint16_t *dst;

	if (r->table == REGSPEC_NONE) {
		return;
	}
	regmap_encode(r, value, w);
	dst = words_at(s->map, r);
	if (dst) {
		memcpy(dst, w, sizeof(uint16_t) * (size_t)regspec_words(r));
	} else {
		*bit_at(s->map, r) = (uint8_t)w[0];
	}
}

/* The value of signal SIG as the master left it; DEF when unmapped. */
static double get(struct slave *s, int sig, double def)
{
	const struct regspec *r = &s->cfg->reg[sig];
	uint16_t bit[1];
	uint16_t *src;

	if (r->table == REGSPEC_NONE) {
		return def;
	}
	src = words_at(s->map, r);
	if (!src) {
		bit[0] = *bit_at(s->map, r);
		src = bit;
	}
	return regmap_decode(r, src);
}

/* Room for every register of the map, per table. */
static modbus_mapping_t *new_map(const struct config_modbus_drive *c)
{
	int top[REGSPEC_HOLDING + 1] = { 0 };

	for (int sig = 0; sig < REGSPEC_SIGNALS; sig++) {
		const struct regspec *r = &c->reg[sig];
		int end = r->address + regspec_words(r);

		if (r->table != REGSPEC_NONE && end > top[r->table]) {
			top[r->table] = end;
		}
	}
	return modbus_mapping_new(top[REGSPEC_COIL], top[REGSPEC_DISCRETE],
				  top[REGSPEC_HOLDING], top[REGSPEC_INPUT]);
}

/* --- the drive ---------------------------------------------------------- */

static double counts(const struct slave *s)
{
	return round(s->motor.plant.x * s->cpr / (2.0 * M_PI));
}

/*
 * A float register that reads NaN: 1.0f written in the register's word
 * and byte order, its exponent then set to all ones (0x3F80 -> 0x7FC0).
 */
static void put_nan(struct slave *s, int sig)
{
	const struct regspec *r = &s->cfg->reg[sig];
	uint16_t *w = words_at(s->map, r);

	if (r->type != REGSPEC_F32 || !w) {
		return;
	}
	put(s, sig, 1.0);
	for (int i = 0; i < 2; i++) {
		w[i] = w[i] == 0x3F80 ? 0x7FC0 : w[i] == 0x803F ? 0xC07F : w[i];
	}
}

/* What the master will read: the motor as the drive measures it. */
static void before_reply(struct slave *s)
{
	put(s, REGSPEC_POSITION, counts(s));
	put(s, REGSPEC_VELOCITY, s->motor.plant.v * s->cpr / (2.0 * M_PI));
	if (s->nan) {
		put_nan(s, REGSPEC_VELOCITY);
	}
	put(s, REGSPEC_FAULT, s->fault);
}

/* What the master wrote: torque, enable, fault reset. */
static void after_reply(struct slave *s, double now)
{
	bool reset = get(s, REGSPEC_FAULT_RESET, 0) != 0;

	if (reset && !s->reset_was_set && !s->sticky) {
		s->fault = 0;
	}
	s->reset_was_set = reset;
	s->enabled = get(s, REGSPEC_ENABLE, 1) != 0;
	s->last_request_s = now;
}

/* The drive's own reactions: torque applied, its watchdog. */
static void drive(struct slave *s, double now)
{
	double wd = get(s, REGSPEC_WATCHDOG, 0);

	if (s->enabled && !s->fault && wd > 0 && now - s->last_request_s > wd) {
		s->fault = WATCHDOG_FAULT;
	}
	s->torque_nm = s->enabled && !s->fault ? get(s, REGSPEC_TORQUE, 0) : 0;
	s->motor.drive_nm = s->torque_nm;
}

/* --- the wire ----------------------------------------------------------- */

/* RTU length of a request from its first 11 bytes; 0: unknown function. */
static int rtu_request_length(const uint8_t *req)
{
	switch (req[1]) {
	case 1: case 2: case 3: case 4: case 5: case 6:
		return 8;
	case 15: case 16:
		return 9 + req[6];
	case 0x17:
		return 13 + req[10];
	default:
		return 0;
	}
}

/* RTU length of the normal reply to a request (PDU at P). */
static int rtu_reply_length(const uint8_t *p)
{
	int n = p[3] << 8 | p[4];

	switch (p[0]) {
	case 1: case 2:
		return 5 + (n + 7) / 8;
	case 3: case 4:
		return 5 + 2 * n;
	case 0x17:
		return 5 + 2 * n;
	default:
		return 8;
	}
}

/* Waits as long as the request and its reply take on the line. */
static void wire_delay(struct mbemu *e, int request_rtu_len, const uint8_t *pdu)
{
	const struct config_modbus *m = &e->cfg.modbus;
	double bits = 1 + m->data_bits + (m->parity ? 1 : 0) + m->stop_bits;
	double chars = request_rtu_len + rtu_reply_length(pdu) + 2 * 3.5;

	if (e->baud > 0) {
		emu_sleep_s(chars * bits / e->baud + e->turnaround_s);
	}
}

static struct slave *find(struct mbemu *e, int id)
{
	for (int i = 0; i < e->n; i++) {
		if (e->s[i].cfg->slave == id) {
			return &e->s[i];
		}
	}
	return NULL;
}

static void trace_request(struct mbemu *e, const uint8_t *req, int len,
			  int slave, const char *answer)
{
	char tag[32], note[96];
	int off = modbus_get_header_length(e->ctx);
	const uint8_t *p = req + off;

	snprintf(tag, sizeof(tag), "slave %d <", slave);
	snprintf(note, sizeof(note), "function 0x%02x at 0x%04x: %s", p[0],
		 p[1] << 8 | p[2], answer);
	emu_trace(e->trace, tag, req, (size_t)len, note);
}

/* Answers one request of LEN bytes. */
static void serve(struct mbemu *e, uint8_t *req, int len)
{
	int off = modbus_get_header_length(e->ctx);
	int id = req[off - 1];
	struct slave *s = find(e, id);
	double now = emu_now_s();

	if (!s || s->mute) {
		trace_request(e, req, len, id, s ? "muted" : "no such slave");
		return;
	}
	s->requests++;
	before_reply(s);
	wire_delay(e, e->tcp ? len - 7 + 3 : len, req + off);
	modbus_set_slave(e->ctx, id);
	if (s->exception_next) {
		modbus_reply_exception(e->ctx, req, s->exception_next);
		trace_request(e, req, len, id, "exception");
		s->exception_next = 0;
		return;
	}
	modbus_reply(e->ctx, req, len, s->map);
	after_reply(s, now);
	trace_request(e, req, len, id, "ok");
}

/* Modbus RTU's CRC-16 (0xA001 reflected, from 0xFFFF), sent low byte first. */
static uint16_t crc16(const uint8_t *p, int n)
{
	uint16_t crc = 0xFFFF;

	for (int i = 0; i < n; i++) {
		crc ^= p[i];
		for (int b = 0; b < 8; b++) {
			crc = crc & 1 ? (uint16_t)(crc >> 1 ^ 0xA001)
				      : (uint16_t)(crc >> 1);
		}
	}
	return crc;
}

/* Reads up to N more bytes within the byte timeout; false on EOF/error. */
static bool read_more(int fd, uint8_t *buf, int *have, int want)
{
	struct timeval tv = { .tv_usec = 20000 };
	fd_set rd;
	ssize_t r;

	while (*have < want) {
		FD_ZERO(&rd);
		FD_SET(fd, &rd);
		if (select(fd + 1, &rd, NULL, NULL, &tv) <= 0) {
			return true; /* a gap: the frame ends short */
		}
		r = read(fd, buf + *have, (size_t)(want - *have));
		if (r <= 0) {
			return false;
		}
		*have += (int)r;
	}
	return true;
}

/*
 * One RTU request, framed by its function code (libmodbus' own receive
 * serves one slave id and then ignores the next frame as that slave's
 * reply: no good for a line of several drives). Returns its length, 0 for
 * a broken frame (dropped), -1 when the line is gone.
 */
static int read_rtu(int fd, uint8_t *req)
{
	int have = 0, len = 0;
	/* the fixed part first: up to the byte count of 15, 16 and 0x17 */
	int head = 8;

	if (!read_more(fd, req, &have, 2)) {
		return -1;
	}
	head = req[1] == 15 || req[1] == 16 ? 7 : req[1] == 0x17 ? 11 : 8;
	if (have == 2 && !read_more(fd, req, &have, head)) {
		return -1;
	}
	len = have >= head ? rtu_request_length(req) : 0;
	if (len > have && len <= MAX_ADU && !read_more(fd, req, &have, len)) {
		return -1;
	}
	if (!len || have != len ||
	    crc16(req, len - 2) != (req[len - 2] | req[len - 1] << 8)) {
		return 0; /* a broken frame: dropped, as a drive would */
	}
	return len;
}

/* Reads and answers one request; false when the line or client is gone. */
static bool receive(struct mbemu *e)
{
	uint8_t req[MAX_ADU];
	int len = e->tcp ? modbus_receive(e->ctx, req) : read_rtu(e->fd, req);

	if (len < 0) {
		return e->tcp && (errno == ETIMEDOUT || errno == EMBBADDATA);
	}
	if (len > 0) {
		serve(e, req, len);
	}
	return true;
}

/* --- control and state -------------------------------------------------- */

/* The input of valve NAME (air, water, suction) reads pressed when ON. */
static bool valve(struct slave *s, const char *name, const char *on)
{
	static const char *const names[CONFIG_VALVES] = { "air", "water",
							  "suction" };

	for (int v = 0; v < CONFIG_VALVES; v++) {
		if (strcmp(name, names[v])) {
			continue;
		}
		if (s->cfg->reg[REGSPEC_VALVE_AIR + v].table == REGSPEC_NONE) {
			fprintf(stderr, "modbus-emu: slave %d: no valve_%s in "
				"its map\n", s->cfg->slave, name);
			return true;
		}
		s->valves = !strcmp(on, "on") ? s->valves | 1u << v
					      : s->valves & ~(1u << v);
		put(s, REGSPEC_VALVE_AIR + v, s->valves >> v & 1u);
		return true;
	}
	return false;
}

/* The tool's input SIGNAL (depth, opening, pedal) reads VALUE. */
static bool tool(struct slave *s, const char *signal, const char *value)
{
	static const char *const names[] = { "depth", "opening", "pedal" };

	for (int k = 0; k < 3; k++) {
		int sig = REGSPEC_TOOL_DEPTH + k;
		double v = k == 2 ? !strcmp(value, "on") : atof(value);

		if (strcmp(signal, names[k])) {
			continue;
		}
		if (s->cfg->reg[sig].table == REGSPEC_NONE) {
			fprintf(stderr, "modbus-emu: slave %d: no tool_%s in "
				"its map\n", s->cfg->slave, signal);
			return true;
		}
		if (k == 0) {
			s->tool_depth_m = v;
		} else if (k == 1) {
			s->tool_opening = v;
		} else {
			s->tool_pedal = v != 0.0;
		}
		put(s, sig, v);
		return true;
	}
	return false;
}

static void change(struct mbemu *e, struct slave *s, int n, char **w,
		   const char *args)
{
	if (!strcmp(w[0], "fault")) {
		s->fault = (uint16_t)(n > 2 ? strtoul(w[2], NULL, 0)
				      : DEFAULT_FAULT);
		s->sticky = n > 3 && !strcmp(w[3], "sticky");
	} else if (!strcmp(w[0], "clear")) {
		s->sticky = false;
	} else if (!strcmp(w[0], "exception")) {
		s->exception_next = n > 2 ? atoi(w[2]) : 4;
	} else if (!strcmp(w[0], "mute") && n > 2) {
		s->mute = !strcmp(w[2], "on");
	} else if (!strcmp(w[0], "nan") && n > 2) {
		s->nan = !strcmp(w[2], "on");
	} else if (!strcmp(w[0], "hand") && n > 2) {
		emu_motor_hand(&s->motor, args);
	} else if (!strcmp(w[0], "move") && n > 2) {
		s->motor.moving = true;
		s->motor.move_rad_s = atof(w[2]) * 2.0 * M_PI / 60.0;
		s->motor.plant.v = s->motor.move_rad_s; /* from now on */
	} else if (!strcmp(w[0], "place") && n > 2) {
		s->motor.plant.x = atof(w[2]) * 2.0 * M_PI / s->cpr;
	} else if (!strcmp(w[0], "valve") && n > 3 && valve(s, w[2], w[3])) {
		/* done */
	} else if (!strcmp(w[0], "tool") && n > 3 && tool(s, w[2], w[3])) {
		/* done */
	} else {
		fprintf(stderr, "modbus-emu: '%s': unknown command\n", w[0]);
	}
	(void)e;
}

static void command(void *ctx, char *line)
{
	struct mbemu *e = ctx;
	char copy[512], *w[6];
	struct slave *s;
	int n;

	snprintf(copy, sizeof(copy), "%s", line);
	emu_trace(e->trace, "control", NULL, 0, copy);
	n = emu_words(line, w, 6);
	if (n == 1 && !strcmp(w[0], "quit")) {
		e->quit = true;
		return;
	}
	s = n >= 2 ? find(e, atoi(w[1])) : NULL;
	if (!s) {
		fprintf(stderr, "modbus-emu: '%s': no such slave\n", copy);
		return;
	}
	change(e, s, n, w, n > 2 ? copy + (w[2] - line) : "");
}

static void write_state(struct mbemu *e)
{
	char text[2048];
	size_t len = 0;

	for (int i = 0; i < e->n && len < sizeof(text); i++) {
		const struct slave *s = &e->s[i];

		len += (size_t)snprintf(
			text + len, sizeof(text) - len,
			"slave=%d axis=%s enabled=%d torque_nm=%.9g counts=%.0f "
			"velocity_counts_s=%.6g fault=0x%04x requests=%lu "
			"mute=%d valves=%u tool_depth_m=%.6g tool_opening=%.4g "
			"tool_pedal=%d\n", s->cfg->slave,
			names_axis(s->axis), s->enabled && !s->fault,
			s->torque_nm, counts(s),
			s->motor.plant.v * s->cpr / (2.0 * M_PI), s->fault,
			s->requests, s->mute, s->valves, s->tool_depth_m,
			s->tool_opening, s->tool_pedal);
	}
	emu_state_write(e->state_path, text);
}

/* Integrates the motors up to now; writes the state file now and then. */
static void advance(struct mbemu *e)
{
	double now = emu_now_s();

	for (int i = 0; i < e->n; i++) {
		drive(&e->s[i], now);
		emu_motor_advance(&e->s[i].motor, now - e->last_s);
	}
	e->last_s = now;
	if (e->state_path && now - e->last_state_s >= STATE_EVERY_S) {
		write_state(e);
		e->last_state_s = now;
	}
}

/* --- the main loop -------------------------------------------------------- */

/* Waits up to 1 ms for the line, a client or a command. */
static void wait_io(struct mbemu *e, fd_set *rd)
{
	struct timeval tv = { .tv_usec = 1000 };
	int top = -1;

	FD_ZERO(rd);
	if (e->fd >= 0) {
		FD_SET(e->fd, rd);
		top = e->fd;
	} else if (e->server >= 0) {
		FD_SET(e->server, rd);
		top = e->server;
	}
	if (e->ctl >= 0) {
		FD_SET(e->ctl, rd);
		top = e->ctl > top ? e->ctl : top;
	}
	if (select(top + 1, rd, NULL, NULL, &tv) < 0) {
		FD_ZERO(rd);
	}
}

static void run(struct mbemu *e)
{
	fd_set rd;

	while (!stop && !e->quit) {
		wait_io(e, &rd);
		if (e->ctl >= 0 && FD_ISSET(e->ctl, &rd)) {
			emu_control_poll(e->ctl, &e->lines, command, e);
		}
		if (e->fd < 0 && e->server >= 0 && FD_ISSET(e->server, &rd)) {
			e->fd = modbus_tcp_accept(e->ctx, &e->server);
		} else if (e->fd >= 0 && FD_ISSET(e->fd, &rd) && !receive(e)) {
			if (!e->tcp) {
				break; /* the line is gone */
			}
			close(e->fd);
			e->fd = -1;
			modbus_set_socket(e->ctx, -1);
		}
		advance(e);
	}
}

/* --- start-up ------------------------------------------------------------ */

static int open_pty(struct mbemu *e, const char *link)
{
	char name[128];
	struct termios t;
	int master, slave;

	if (openpty(&master, &slave, name, NULL, NULL) < 0) {
		perror("modbus-emu: openpty");
		return -1;
	}
	/* raw from the start: no echo before the daemon sets the line up;
	 * SLAVE stays open so the master never sees a hang-up meanwhile */
	tcgetattr(slave, &t);
	cfmakeraw(&t);
	tcsetattr(slave, TCSANOW, &t);
	unlink(link);
	if (symlink(name, link) < 0) {
		perror("modbus-emu: symlink");
		return -1;
	}
	e->ctx = modbus_new_rtu(link, 115200, 'N', 8, 1);
	e->fd = master;
	return e->ctx ? modbus_set_socket(e->ctx, master) : -1;
}

static int open_tty(struct mbemu *e, const char *path)
{
	static const char parity[] = { 'N', 'E', 'O' };
	const struct config_modbus *m = &e->cfg.modbus;

	e->ctx = modbus_new_rtu(path, m->baud, parity[m->parity], m->data_bits,
				m->stop_bits);
	if (!e->ctx || modbus_connect(e->ctx) < 0) {
		fprintf(stderr, "modbus-emu: %s: %s\n", path,
			modbus_strerror(errno));
		return -1;
	}
	e->fd = modbus_get_socket(e->ctx);
	return 0;
}

static int open_tcp(struct mbemu *e, int port)
{
	e->tcp = true;
	e->ctx = modbus_new_tcp("127.0.0.1", port);
	e->server = e->ctx ? modbus_tcp_listen(e->ctx, 1) : -1;
	if (e->server < 0) {
		fprintf(stderr, "modbus-emu: port %d: %s\n", port,
			modbus_strerror(errno));
		return -1;
	}
	return 0;
}

static int load(struct mbemu *e, const char *path,
		const struct emu_motor_params *motor)
{
	char err[512];

	config_defaults(&e->cfg);
	if (config_load(&e->cfg, path, err, sizeof(err))) {
		fprintf(stderr, "modbus-emu: %s\n", err);
		return -1;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		struct slave *s = &e->s[e->n];

		if (config_axis_backend(&e->cfg, a) != CONFIG_DRIVE_MODBUS) {
			continue;
		}
		s->axis = a;
		s->cfg = &e->cfg.modbus_drive[a];
		s->cpr = e->cfg.axis[a].counts_per_rev;
		s->map = new_map(s->cfg);
		emu_motor_init(&s->motor, motor);
		if (!s->map) {
			return -1;
		}
		for (int v = 0; v < CONFIG_VALVES; v++) {
			put(s, REGSPEC_VALVE_AIR + v, 0); /* released */
		}
		e->n++;
	}
	if (!e->n) {
		fprintf(stderr, "modbus-emu: %s: no axis with backend modbus "
			"(and [rig] backend = drives)\n", path);
	}
	return e->n ? 0 : -1;
}

static void usage(void)
{
	fprintf(stderr,
		"usage: modbus-emu --config FILE (--pty LINK | --tty PATH | "
		"--listen PORT) [options]\n"
		"  --config FILE    endosimd's configuration: slaves and maps\n"
		"  --pty LINK       RTU on a new pty, its other end linked at LINK\n"
		"  --tty PATH       RTU on an existing tty\n"
		"  --listen PORT    TCP on 127.0.0.1:PORT\n"
		"  --baud N         reply as late as an N baud line would (0: "
		"at once)\n"
		"  --turnaround S   and the drive's own reply time, s\n"
		"  -o inertia=|viscous=|coulomb=|hold=VALUE   the motors, SI\n"
		"  --control FIFO --state FILE --trace FILE\n");
}

struct options {
	const char *config, *pty, *tty, *control, *state, *trace;
	int port;
	struct emu_motor_params motor;
};

static int parse(int argc, char **argv, struct mbemu *e, struct options *o)
{
	static const struct option opts[] = {
		{ "config", required_argument, NULL, 'c' },
		{ "pty", required_argument, NULL, 'p' },
		{ "tty", required_argument, NULL, 't' },
		{ "listen", required_argument, NULL, 'l' },
		{ "baud", required_argument, NULL, 'b' },
		{ "turnaround", required_argument, NULL, 'a' },
		{ "control", required_argument, NULL, 'C' },
		{ "state", required_argument, NULL, 'S' },
		{ "trace", required_argument, NULL, 'T' },
		{ NULL, 0, NULL, 0 },
	};
	int c;

	while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
		switch (c) {
		case 'c': o->config = optarg; break;
		case 'p': o->pty = optarg; break;
		case 't': o->tty = optarg; break;
		case 'l': o->port = atoi(optarg); break;
		case 'b': e->baud = atoi(optarg); break;
		case 'a': e->turnaround_s = atof(optarg); break;
		case 'C': o->control = optarg; break;
		case 'S': o->state = optarg; break;
		case 'T': o->trace = optarg; break;
		case 'o':
			if (!emu_motor_option(&o->motor, optarg)) {
				return -1;
			}
			break;
		default:
			return -1;
		}
	}
	return o->config && !!o->pty + !!o->tty + !!o->port == 1 &&
			       optind == argc
		       ? 0 : -1;
}

static void on_signal(int sig)
{
	(void)sig;
	stop = 1;
}

int main(int argc, char **argv)
{
	static struct mbemu e = { .server = -1, .fd = -1 };
	struct options o = { .motor = EMU_MOTOR_DEFAULTS };
	int r;

	if (parse(argc, argv, &e, &o)) {
		usage();
		return 2;
	}
	log_init("modbus-emu", LOG_WARNING);
	if (load(&e, o.config, &o.motor)) {
		return 1;
	}
	r = o.pty ? open_pty(&e, o.pty) : o.tty ? open_tty(&e, o.tty)
						: open_tcp(&e, o.port);
	if (r) {
		return 1;
	}
	e.ctl = o.control ? emu_control_open(o.control) : -1;
	e.trace = o.trace ? fopen(o.trace, "w") : NULL;
	e.state_path = o.state;
	e.last_s = emu_now_s();
	signal(SIGTERM, on_signal);
	signal(SIGINT, on_signal);
	signal(SIGPIPE, SIG_IGN);
	printf("ready\n");
	fflush(stdout);
	run(&e);
	if (o.pty) {
		unlink(o.pty);
	}
	return 0;
}
