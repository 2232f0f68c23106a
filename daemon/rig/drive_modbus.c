/*
 * drive_modbus.c - the modbus backend (drive.h): brushed DC wheel drives on
 * one Modbus RTU line or TCP connection (libmodbus 3.1), each with its
 * register map from the configuration (conf/regspec.h, rig/regmap.h).
 *
 * One exchange, per drive: the torque setpoint written (when enabled), then
 * the feedback registers read, grouped per table into as few reads as fit
 * (125 registers or bits each); with combined_0x17 both in one
 * write-and-read transaction (function 0x17). The handle's valves
 * ([modbus.NAME] valve_*) are feedback like the rest: a valve in a table
 * the feedback already reads, within its span, costs nothing more; valves
 * on discrete inputs (function 0x02) add one read per drive, whatever
 * their number, when within 125 bits of each other. The tool in the
 * working channel ([modbus.NAME] tool_*) too: its depth and opening on
 * input registers (function 0x04) one read per drive when within 125
 * registers of each other, its pedal with the valves' discrete inputs.
 *
 * libmodbus' failure modes (measured; see the notes): timeouts are set short
 * and a late reply is flushed; its link recovery (which retries for seconds)
 * stays off; EIO, ECONNRESET, EPIPE and EBADF mean the connection is gone:
 * the bus thread closes it and reconnects; modbus_connect() is checked.
 */
#include <errno.h>
#include <math.h>
#include <modbus.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proto/names.h"
#include "rig/drive.h"
#include "rig/regmap.h"
#include "base/log.h"
#include "base/mono.h"

#define READ_MAX 125 /* registers or bits one read may take */
/* The signals read each exchange; position first: with 0x17, read[0]. */
static const int feedback[] = { REGSPEC_POSITION, REGSPEC_VELOCITY,
				REGSPEC_FAULT, REGSPEC_VALVE_AIR,
				REGSPEC_VALVE_WATER, REGSPEC_VALVE_SUCTION,
				REGSPEC_TOOL_DEPTH, REGSPEC_TOOL_OPENING,
				REGSPEC_TOOL_PEDAL };
#define FEEDBACK (sizeof(feedback) / sizeof(feedback[0]))
#define PLAN_MAX FEEDBACK /* at most one read each */

/* One read of a span of one table. */
struct mb_read {
	uint8_t table;
	uint16_t address, count;
	uint16_t regs[READ_MAX]; /* bits land one per element */
};

struct mb_drive {
	const struct config_modbus_drive *cfg;
	struct mb_read read[PLAN_MAX];
	int reads;
	int of[REGSPEC_SIGNALS]; /* the read holding each feedback signal */
	bool enabled;
	int up_step;
};

struct mb {
	struct drive d;
	struct config_modbus bus;
	struct config_modbus_drive drives[DRIVE_MAX];
	struct mb_drive dr[DRIVE_MAX];
	modbus_t *ctx;
};

static struct mb *to_mb(struct drive *d)
{
	return (struct mb *)d;
}

/* --- the read plan -------------------------------------------------- */

/* Adds signal S to a read of its table that can take it, or a new one. */
static void plan_signal(struct mb_drive *dr, int s)
{
	const struct regspec *r = &dr->cfg->reg[s];
	int lo = r->address, hi = r->address + regspec_words(r);

	for (int k = 0; k < dr->reads; k++) {
		struct mb_read *rd = &dr->read[k];
		int a = rd->address < lo ? rd->address : lo;
		int b = rd->address + rd->count > hi ? rd->address + rd->count
						     : hi;

		if (rd->table == r->table && b - a <= READ_MAX) {
			rd->address = (uint16_t)a;
			rd->count = (uint16_t)(b - a);
			dr->of[s] = k;
			return;
		}
	}
	dr->read[dr->reads] = (struct mb_read){ .table = r->table,
						.address = r->address,
						.count = (uint16_t)(hi - lo) };
	dr->of[s] = dr->reads++;
}

static void plan(struct mb_drive *dr)
{
	for (size_t k = 0; k < FEEDBACK; k++) {
		if (dr->cfg->reg[feedback[k]].table != REGSPEC_NONE) {
			plan_signal(dr, feedback[k]);
		}
	}
}

/* The value of feedback signal S after its read. */
static double feedback_value(const struct mb_drive *dr, int s)
{
	const struct regspec *r = &dr->cfg->reg[s];
	const struct mb_read *rd = &dr->read[dr->of[s]];

	return regmap_decode(r, rd->regs + (r->address - rd->address));
}

/* --- transactions --------------------------------------------------- */

static bool connection_lost(int e)
{
	return e == EIO || e == ECONNRESET || e == EPIPE || e == EBADF ||
	       e == ENOTCONN || e == ECONNREFUSED || e == ENXIO ||
	       e == ENODEV;
}

/* Maps libmodbus' errno after a failed call on drive I. */
static int mb_fail(struct mb *m, int i, const char *what, int address)
{
	int e = errno;
	int err = e == ETIMEDOUT ? -ETIMEDOUT
		  : e == EMBBADCRC ? -EBADMSG
		  : e >= EMBXILFUN && e <= EMBXGTAR ? -EREMOTEIO
		  : e >= EMBBADDATA && e <= EMBBADSLAVE ? -EPROTO
		  : connection_lost(e) ? -ENODEV : -EIO;

	if (err == -ETIMEDOUT || err == -EBADMSG || err == -EPROTO) {
		modbus_flush(m->ctx); /* a late reply must not answer the next */
	}
	return drive_fail(&m->d, err == -ENODEV ? -1 : i, err,
			  "slave %d: %s 0x%04x: %s", m->dr[i].cfg->slave, what,
			  address, modbus_strerror(e));
}

static int write_signal(struct mb *m, int i, int s, double value)
{
	const struct regspec *r = &m->dr[i].cfg->reg[s];
	uint16_t w[REGSPEC_MAX_WORDS];
	uint64_t t0 = mono_ns();
	int rc;

	if (r->table == REGSPEC_NONE) {
		return 0;
	}
	regmap_encode(r, value, w);
	modbus_set_slave(m->ctx, m->dr[i].cfg->slave);

	if (r->table == REGSPEC_COIL) {
		rc = modbus_write_bit(m->ctx, r->address, w[0]);
	} else if (regspec_words(r) == 1) {
		rc = modbus_write_register(m->ctx, r->address, w[0]);
	} else {
		rc = modbus_write_registers(m->ctx, r->address, 2, w);
	}
	if (rc < 0) {
		return mb_fail(m, i, "writing", r->address);
	}
	drive_count_txn(&m->d, t0);
	return 0;
}

static int read_span(struct mb *m, int i, struct mb_read *rd)
{
	uint8_t bits[READ_MAX];
	uint64_t t0 = mono_ns();
	int rc;

	switch (rd->table) {
	case REGSPEC_COIL:
	case REGSPEC_DISCRETE:
		rc = rd->table == REGSPEC_COIL
			     ? modbus_read_bits(m->ctx, rd->address, rd->count,
						bits)
			     : modbus_read_input_bits(m->ctx, rd->address,
						      rd->count, bits);
		for (int k = 0; rc > 0 && k < rd->count; k++) {
			rd->regs[k] = bits[k];
		}
		break;
	case REGSPEC_INPUT:
		rc = modbus_read_input_registers(m->ctx, rd->address, rd->count,
						 rd->regs);
		break;
	default:
		rc = modbus_read_registers(m->ctx, rd->address, rd->count,
					   rd->regs);
		break;
	}
	if (rc < 0) {
		return mb_fail(m, i, "reading", rd->address);
	}
	drive_count_txn(&m->d, t0);
	return 0;
}

/* Function 0x17: the torque written and the feedback read at once. */
static int write_read(struct mb *m, int i, double torque)
{
	struct mb_drive *dr = &m->dr[i];
	const struct regspec *t = &dr->cfg->reg[REGSPEC_TORQUE];
	struct mb_read *rd = &dr->read[0];
	uint16_t w[REGSPEC_MAX_WORDS];
	uint64_t t0 = mono_ns();

	regmap_encode(t, torque, w);
	if (modbus_write_and_read_registers(m->ctx, t->address,
					    regspec_words(t), w, rd->address,
					    rd->count, rd->regs) < 0) {
		return mb_fail(m, i, "write-and-read (0x17) at", t->address);
	}
	drive_count_txn(&m->d, t0);
	return 0;
}

/* The tool's signals DR reads (their values are SI already: the
 * registers' scale and offset), into T. */
static void tool_of(const struct mb_drive *dr, struct drive_tool *t)
{
	const struct regspec *reg = dr->cfg->reg;

	if (reg[REGSPEC_TOOL_DEPTH].table != REGSPEC_NONE) {
		t->depth_m = feedback_value(dr, REGSPEC_TOOL_DEPTH);
	}
	if (reg[REGSPEC_TOOL_OPENING].table != REGSPEC_NONE) {
		t->opening = feedback_value(dr, REGSPEC_TOOL_OPENING);
	}
	t->pedal = reg[REGSPEC_TOOL_PEDAL].table != REGSPEC_NONE &&
		   feedback_value(dr, REGSPEC_TOOL_PEDAL) != 0.0;
}

/* The one place where register values meet SI. */
static void to_si(const struct mb *m, int i, struct drive_sample *s)
{
	const struct mb_drive *dr = &m->dr[i];
	const struct drive_units *u = &m->d.units[i];
	double code = dr->cfg->reg[REGSPEC_FAULT].table != REGSPEC_NONE
			      ? feedback_value(dr, REGSPEC_FAULT) : 0.0;

	s->position = feedback_value(dr, REGSPEC_POSITION) * u->si_per_count;
	s->velocity = dr->cfg->reg[REGSPEC_VELOCITY].table != REGSPEC_NONE
			      ? feedback_value(dr, REGSPEC_VELOCITY) *
					u->si_per_count
			      : 0.0;
	s->enabled = dr->enabled;
	s->fault = code != 0.0;
	s->code = (uint32_t)(int64_t)code;
	s->valves = 0;
	for (int v = 0; v < CONFIG_VALVES; v++) {
		int sig = REGSPEC_VALVE_AIR + v;

		if (dr->cfg->reg[sig].table != REGSPEC_NONE &&
		    feedback_value(dr, sig) != 0.0) {
			s->valves |= 1u << v;
		}
	}
	tool_of(dr, &s->tool);
}

static int exchange_one(struct mb *m, int i, double setpoint,
			struct drive_sample *s)
{
	struct mb_drive *dr = &m->dr[i];
	double torque = dr->enabled ? setpoint * m->d.units[i].motor_nm_per_si
				    : 0.0;
	int r = 0, k = 0;

	modbus_set_slave(m->ctx, dr->cfg->slave);
	if (dr->cfg->combined_0x17) {
		r = write_read(m, i, torque);
		k = 1; /* read[0] came with it: the rest, valves elsewhere */
	} else if (dr->enabled) {
		r = write_signal(m, i, REGSPEC_TORQUE, torque);
	}
	for (; !r && k < dr->reads; k++) {
		r = read_span(m, i, &dr->read[k]);
	}
	if (!r) {
		to_si(m, i, s);
	}
	return r;
}

static int mb_exchange(struct drive *d, const double *setpoint,
		       struct drive_sample *s)
{
	struct mb *m = to_mb(d);
	int r = 0;

	for (int i = 0; !r && i < d->n; i++) {
		r = exchange_one(m, i, setpoint[i], &s[i]);
	}
	return r;
}

/* --- opening ---------------------------------------------------------- */

static modbus_t *new_context(struct mb *m)
{
	static const char parity[] = { 'N', 'E', 'O' };
	char port[16];

	if (m->bus.transport == CONFIG_MODBUS_TCP) {
		snprintf(port, sizeof(port), "%d", m->bus.port);
		return modbus_new_tcp_pi(m->bus.host, port);
	}
	return modbus_new_rtu(m->bus.device, m->bus.baud,
			      parity[m->bus.parity], m->bus.data_bits,
			      m->bus.stop_bits);
}

static void set_timeouts(struct mb *m)
{
	double rt = m->bus.response_timeout_s, bt = m->bus.byte_timeout_s;

	modbus_set_response_timeout(m->ctx, (uint32_t)rt,
				    (uint32_t)((rt - floor(rt)) * 1e6));
	modbus_set_byte_timeout(m->ctx, (uint32_t)bt,
				(uint32_t)((bt - floor(bt)) * 1e6));
	modbus_set_error_recovery(m->ctx, MODBUS_ERROR_RECOVERY_NONE);
}

static int connect_bus(struct mb *m)
{
	m->ctx = new_context(m);
	if (!m->ctx) {
		return drive_fail(&m->d, -1, -ENODEV, "cannot set up: %s",
				  modbus_strerror(errno));
	}
	set_timeouts(m);
	if (modbus_connect(m->ctx) < 0) {
		return drive_fail(&m->d, -1, -ENODEV, "cannot %s: %s",
				  m->bus.transport == CONFIG_MODBUS_TCP
					  ? "connect" : "open the line",
				  modbus_strerror(errno));
	}
	if (m->bus.transport == CONFIG_MODBUS_RTU && m->bus.rs485 &&
	    modbus_rtu_set_serial_mode(m->ctx, MODBUS_RTU_RS485) < 0) {
		return drive_fail(&m->d, -1, -ENXIO, "cannot switch to RS-485 "
				  "mode: %s", modbus_strerror(errno));
	}
	/* a reply to a daemon that died mid-transaction must not answer us */
	modbus_flush(m->ctx);
	return 0;
}

/* Drive I starts disabled with no torque, and answers. */
static int check_drive(struct mb *m, int i)
{
	char why[sizeof(m->d.why)];
	struct drive_sample s;
	int r;

	m->dr[i].enabled = false;
	m->dr[i].up_step = 0;
	r = write_signal(m, i, REGSPEC_TORQUE, 0.0);
	r = r ? r : write_signal(m, i, REGSPEC_ENABLE, 0.0);
	r = r ? r : exchange_one(m, i, 0.0, &s);
	if (!r) {
		return 0;
	}
	snprintf(why, sizeof(why), "%s", m->d.why);
	return drive_fail(&m->d, -1, r == -ENODEV ? -ENODEV : -ENXIO,
			  "%s (does the drive for %s answer?)", why,
			  names_axis(m->d.axis[i]));
}

static void mb_close(struct drive *d)
{
	struct mb *m = to_mb(d);

	if (m->ctx) {
		modbus_close(m->ctx);
		modbus_free(m->ctx);
		m->ctx = NULL;
	}
	for (int i = 0; i < d->n; i++) {
		m->dr[i].enabled = false;
	}
}

static int mb_open(struct drive *d)
{
	struct mb *m = to_mb(d);
	int r = connect_bus(m);

	for (int i = 0; !r && i < d->n; i++) {
		r = check_drive(m, i);
	}
	if (r) {
		mb_close(d);
	}
	return r;
}

/* --- enabling --------------------------------------------------------- */

static int mb_bring_up(struct drive *d, int i)
{
	struct mb *m = to_mb(d);
	struct mb_drive *dr = &m->dr[i];
	int r = 0;

	switch (dr->up_step) {
	case 0:
		r = write_signal(m, i, REGSPEC_TORQUE, 0.0);
		break;
	case 1:
		r = dr->cfg->watchdog_s > 0
			    ? write_signal(m, i, REGSPEC_WATCHDOG,
					   dr->cfg->watchdog_s)
			    : 0;
		break;
	default:
		r = write_signal(m, i, REGSPEC_ENABLE, 1.0);
		dr->enabled = r == 0;
		dr->up_step = 0;
		return r;
	}
	dr->up_step = r ? 0 : dr->up_step + 1;
	return r ? r : 1;
}

static int mb_bring_down(struct drive *d, int i)
{
	struct mb *m = to_mb(d);
	int r1, r2;

	m->dr[i].enabled = false;
	m->dr[i].up_step = 0;
	r1 = write_signal(m, i, REGSPEC_TORQUE, 0.0);
	r2 = write_signal(m, i, REGSPEC_ENABLE, 0.0);
	return r1 ? r1 : r2;
}

static int mb_clear_fault(struct drive *d, int i)
{
	struct mb *m = to_mb(d);
	int r = write_signal(m, i, REGSPEC_FAULT_RESET, 1.0);

	return r ? r : write_signal(m, i, REGSPEC_FAULT_RESET, 0.0);
}

static void mb_destroy(struct drive *d)
{
	mb_close(d);
	free(d);
}

static const char *mb_describe_fault(uint32_t code)
{
	(void)code;
	return "the drive's own code: see its manual";
}

static const struct drive_ops mb_ops = {
	.kind = "modbus",
	.open = mb_open,
	.bring_up = mb_bring_up,
	.exchange = mb_exchange,
	.bring_down = mb_bring_down,
	.clear_fault = mb_clear_fault,
	.close = mb_close,
	.destroy = mb_destroy,
	.describe_fault = mb_describe_fault,
};

static void set_name(struct mb *m)
{
	static const char parity[] = { 'N', 'E', 'O' };
	const struct config_modbus *b = &m->bus;

	if (b->transport == CONFIG_MODBUS_TCP) {
		snprintf(m->d.name, sizeof(m->d.name), "modbus tcp %s:%d",
			 b->host, b->port);
	} else {
		snprintf(m->d.name, sizeof(m->d.name), "modbus rtu %s %d %d%c%d",
			 b->device, b->baud, b->data_bits, parity[b->parity],
			 b->stop_bits);
	}
}

struct drive *drive_modbus_create(const struct config *cfg)
{
	struct mb *m = calloc(1, sizeof(*m));

	if (!m) {
		log_err("modbus: out of memory");
		return NULL;
	}
	m->d.ops = &mb_ops;
	m->bus = cfg->modbus;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		int i = m->d.n;

		if (config_axis_backend(cfg, a) != CONFIG_DRIVE_MODBUS) {
			continue;
		}
		m->drives[i] = cfg->modbus_drive[a];
		m->dr[i].cfg = &m->drives[i];
		plan(&m->dr[i]);
		m->d.axis[i] = a;
		drive_units_init(&m->d.units[i], cfg, a);
		m->d.valves[i] = config_axis_valves(cfg, a);
		m->d.tool[i] = config_axis_tool(cfg, a);
		snprintf(m->d.unit[i], sizeof(m->d.unit[i]), "slave %d",
			 m->drives[i].slave);
		m->d.n++;
	}
	set_name(m);
	return &m->d;
}
