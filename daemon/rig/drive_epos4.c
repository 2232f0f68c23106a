/*
 * drive_epos4.c - the epos4-usb backend (drive.h): one maxon EPOS4 on USB,
 * found by VID:PID and serial number with libusb-1.0, spoken to with the
 * EPOS4 frame protocol (epos4_frame.h) and driven through the CiA 402 state
 * machine (canopen.h) in cyclic synchronous torque mode.
 *
 * One exchange is four request/reply pairs (the device takes one request
 * at a time): WriteObject target torque 0x6071 (when enabled), ReadObject
 * position 0x6064, velocity 0x606C and statusword 0x6041; the error code
 * 0x603F is read once when a fault appears. A drive that reads some of the
 * handle's valves ([epos4.NAME] valve_*_bit) adds a fifth, ReadObject
 * digital inputs 0x60FD: the frame protocol reads one object per request
 * (no PDOs over USB), so the valves cost one more round trip per exchange.
 * The tool in the working channel ([epos4.NAME] tool_*) likewise: its
 * depth one ReadObject of the additional position actual values
 * 0x60E4:N (the auxiliary encoder, the drive's sensor N), its handle's
 * opening one of an analogue input 0x3160:N (mV), its pedal a bit of
 * 0x60FD, read once for the valves and the pedal: up to three more round
 * trips.
 * Bringing a drive up sets its heartbeat consumer 0x1016:01 to
 * [epos4.NAME] watchdog_s.
 */
#include <errno.h>
#include <libusb.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proto/names.h"
#include "rig/canopen.h"
#include "rig/drive.h"
#include "rig/epos4_frame.h"
#include "base/log.h"
#include "base/mono.h"

#define UP_TIMEOUT_NS ENDOSIM_NS_PER_S /* to reach operation enabled */
#define IN_BUF 512

struct epos4 {
	struct drive d;
	struct config_epos4 cfg;
	int counts_per_rev;
	unsigned int timeout_ms;
	libusb_context *ctx;
	libusb_device_handle *h;
	uint8_t ep_in, ep_out;
	double rated_nm;        /* motor rated torque 0x6076, N m */
	double rpm_per_unit;    /* velocity unit 0x60A9 in rpm */
	bool enabled;           /* brought up: target torque is written */
	int up_step;
	uint64_t up_deadline_ns;
	enum canopen_state state; /* as the last exchange read it */
	uint16_t statusword;
	bool fault_read;        /* 0x603F read since the fault appeared */
	uint32_t fault_code;
	struct epos4_decoder dec;
};

static struct epos4 *to_epos4(struct drive *d)
{
	return (struct epos4 *)d;
}

/* --- transport ------------------------------------------------------ */

static int usb_fail(struct epos4 *e, int r, const char *what, int index,
		    int sub)
{
	if (r == LIBUSB_ERROR_NO_DEVICE) {
		return drive_fail(&e->d, -1, -ENODEV, "%s 0x%04x/%02x: "
				  "disconnected", what, index, sub);
	}
	if (r == LIBUSB_ERROR_TIMEOUT) {
		return drive_fail(&e->d, 0, -ETIMEDOUT, "%s 0x%04x/%02x: no "
				  "reply within %u ms%s", what, index, sub,
				  e->timeout_ms,
				  epos4_decoder_busy(&e->dec)
					  ? " (reply truncated)" : "");
	}
	if (r == LIBUSB_ERROR_PIPE) {
		libusb_clear_halt(e->h, e->ep_in);
		libusb_clear_halt(e->h, e->ep_out);
	}
	return drive_fail(&e->d, 0, -EIO, "%s 0x%04x/%02x: USB: %s", what,
			  index, sub, libusb_strerror(r));
}

static int frame_fail(struct epos4 *e, int r, const char *what, int index,
		      int sub)
{
	return drive_fail(&e->d, 0, r, "%s 0x%04x/%02x: reply %s", what,
			  index, sub,
			  r == -EBADMSG ? "failed its CRC" : "badly framed");
}

/* Sends REQ, then reads until a whole reply frame is in RSP. */
static int transact(struct epos4 *e, const struct epos4_frame *req,
		    struct epos4_frame *rsp, const char *what, int index,
		    int sub)
{
	uint8_t out[EPOS4_FRAME_MAX_BYTES], in[IN_BUF];
	size_t n = epos4_frame_encode(req, out, sizeof(out));
	uint64_t t0 = mono_ns();
	int done, r;

	epos4_decoder_reset(&e->dec);
	r = libusb_bulk_transfer(e->h, e->ep_out, out, (int)n, &done,
				 e->timeout_ms);
	while (!r) {
		r = libusb_bulk_transfer(e->h, e->ep_in, in, sizeof(in), &done,
					 e->timeout_ms);
		for (int i = 0; !r && i < done; i++) {
			int f = epos4_decoder_feed(&e->dec, in[i], rsp);

			if (f < 0) {
				return frame_fail(e, f, what, index, sub);
			}
			if (f > 0) {
				drive_count_txn(&e->d, t0);
				return 0;
			}
		}
	}
	return usb_fail(e, r, what, index, sub);
}

/* ReadObject (VALUE out) or WriteObject (VALUE in) of INDEX/SUB. */
static int sdo(struct epos4 *e, bool write, uint16_t index, uint8_t sub,
	       uint32_t *value)
{
	const char *what = write ? "WriteObject" : "ReadObject";
	struct epos4_frame req, rsp;
	uint32_t abort, v;
	const char *text;
	int r;

	if (write) {
		epos4_write_request(&req, (uint8_t)e->cfg.node_id, index, sub,
				    *value);
	} else {
		epos4_read_request(&req, (uint8_t)e->cfg.node_id, index, sub);
	}
	r = transact(e, &req, &rsp, what, index, sub);
	if (r) {
		return r;
	}
	if (epos4_parse_response(&rsp, req.opcode, &abort, &v)) {
		return drive_fail(&e->d, 0, -EPROTO, "%s 0x%04x/%02x: reply "
				  "with opcode 0x%02x and %u words", what,
				  index, sub, rsp.opcode, rsp.len_words);
	}
	if (abort) {
		text = canopen_abort_text(abort);
		return drive_fail(&e->d, 0, -EREMOTEIO, "%s 0x%04x/%02x: the "
				  "drive refused: abort code 0x%08x (%s)", what,
				  index, sub, abort,
				  text ? text : "not a CiA 301 code");
	}
	if (!write) {
		*value = v;
	}
	return 0;
}

static int read_object(struct epos4 *e, uint16_t index, uint32_t *value)
{
	return sdo(e, false, index, 0, value);
}

static int write_object(struct epos4 *e, uint16_t index, uint32_t value)
{
	return sdo(e, true, index, 0, &value);
}

/* --- opening ---------------------------------------------------------- */

/* Opens DEV if it is the configured drive; the serials seen go to SEEN. */
static bool try_device(struct epos4 *e, libusb_device *dev, char *seen,
		       size_t size)
{
	struct libusb_device_descriptor desc;
	unsigned char serial[128] = "";
	libusb_device_handle *h;

	if (libusb_get_device_descriptor(dev, &desc) ||
	    desc.idVendor != e->cfg.vid || desc.idProduct != e->cfg.pid ||
	    libusb_open(dev, &h)) {
		return false;
	}
	if (desc.iSerialNumber) {
		libusb_get_string_descriptor_ascii(h, desc.iSerialNumber, serial,
						   sizeof(serial));
	}
	if (!e->cfg.serial[0] || !strcmp(e->cfg.serial, (char *)serial)) {
		e->h = h;
		return true;
	}
	snprintf(seen + strlen(seen), size - strlen(seen), "%s'%s'",
		 seen[0] ? ", " : "", serial);
	libusb_close(h);
	return false;
}

static int find_device(struct epos4 *e)
{
	libusb_device **list;
	char seen[160] = "";
	ssize_t n = libusb_get_device_list(e->ctx, &list);

	for (ssize_t i = 0; i < n && !e->h; i++) {
		try_device(e, list[i], seen, sizeof(seen));
	}
	if (n >= 0) {
		libusb_free_device_list(list, 1);
	}
	if (e->h) {
		return 0;
	}
	return drive_fail(&e->d, -1, -ENODEV, "no USB device %04x:%04x%s%s%s "
			  "found%s%s", e->cfg.vid, e->cfg.pid,
			  e->cfg.serial[0] ? " with serial '" : "",
			  e->cfg.serial, e->cfg.serial[0] ? "'" : "",
			  seen[0] ? "; there are serials " : "", seen);
}

/* The first bulk IN and OUT endpoints of interface 0. */
static int find_endpoints(struct epos4 *e)
{
	struct libusb_config_descriptor *c;
	const struct libusb_interface_descriptor *alt;

	if (libusb_get_active_config_descriptor(libusb_get_device(e->h), &c)) {
		return drive_fail(&e->d, -1, -ENXIO, "no USB configuration");
	}
	alt = c->bNumInterfaces ? &c->interface[0].altsetting[0] : NULL;
	for (int i = 0; alt && i < alt->bNumEndpoints; i++) {
		const struct libusb_endpoint_descriptor *ep = &alt->endpoint[i];

		if ((ep->bmAttributes & 3) != LIBUSB_TRANSFER_TYPE_BULK) {
			continue;
		}
		if (ep->bEndpointAddress & LIBUSB_ENDPOINT_IN) {
			e->ep_in = e->ep_in ? e->ep_in : ep->bEndpointAddress;
		} else {
			e->ep_out = e->ep_out ? e->ep_out : ep->bEndpointAddress;
		}
	}
	libusb_free_config_descriptor(c);
	if (!e->ep_in || !e->ep_out) {
		return drive_fail(&e->d, -1, -ENXIO, "interface 0 has no bulk "
				  "IN and OUT endpoints: not an EPOS4");
	}
	return 0;
}

/* The drive is a CiA 402 drive whose units this backend understands. */
static int check_drive(struct epos4 *e)
{
	uint32_t type, rated, unit;
	int r = read_object(e, CANOPEN_DEVICE_TYPE, &type);

	if (!r && (type & 0xFFFF) != CANOPEN_DEVICE_PROFILE_DRIVE) {
		return drive_fail(&e->d, -1, -ENXIO, "not a CiA 402 drive "
				  "(device type 0x%08x)", type);
	}
	r = r ? r : read_object(e, CANOPEN_RATED_TORQUE, &rated);
	if (!r && rated == 0) {
		return drive_fail(&e->d, -1, -ENXIO, "motor rated torque "
				  "0x6076 is 0: set up the motor data first");
	}
	r = r ? r : read_object(e, CANOPEN_SI_UNIT_VELOCITY, &unit);
	if (!r && (unit & 0x00FFFFFF) != CANOPEN_SI_UNIT_RPM) {
		return drive_fail(&e->d, -1, -ENXIO, "velocity unit 0x60A9 is "
				  "0x%08x: only rpm (with a prefix) is "
				  "supported", unit);
	}
	if (r) {
		return r;
	}
	e->rated_nm = rated * e->cfg.rated_torque_unit_n_m;
	e->rpm_per_unit = pow(10.0, (int8_t)(unit >> 24));
	return 0;
}

static int epos4_open(struct drive *d)
{
	struct epos4 *e = to_epos4(d);
	int r;

	e->enabled = false;
	e->up_step = 0;
	e->fault_read = false;
	if (libusb_init(&e->ctx)) {
		e->ctx = NULL;
		return drive_fail(d, -1, -ENODEV, "libusb cannot start");
	}
	r = find_device(e);
	if (!r && libusb_claim_interface(e->h, 0)) {
		r = drive_fail(d, -1, -ENODEV, "cannot claim its interface 0 "
			       "(in use by another program?)");
	}
	r = r ? r : find_endpoints(e);
	r = r ? r : check_drive(e);
	/* whatever it did before, it starts disabled with no torque */
	r = r ? r : write_object(e, CANOPEN_TARGET_TORQUE, 0);
	r = r ? r : write_object(e, CANOPEN_CONTROLWORD,
				 CANOPEN_CW_DISABLE_VOLTAGE);
	if (r) {
		d->ops->close(d);
	}
	return r;
}

static void epos4_close(struct drive *d)
{
	struct epos4 *e = to_epos4(d);

	if (e->h) {
		libusb_release_interface(e->h, 0);
		libusb_close(e->h);
		e->h = NULL;
	}
	if (e->ctx) {
		libusb_exit(e->ctx);
		e->ctx = NULL;
	}
	e->ep_in = e->ep_out = 0;
	e->enabled = false;
}

/* --- operation -------------------------------------------------------- */

/* The one place where SI meets the drive's units. */
static int16_t torque_permille(const struct epos4 *e, double setpoint)
{
	double pm = setpoint * e->d.units[0].motor_nm_per_si / e->rated_nm *
		    1000.0;

	return (int16_t)lround(fmin(fmax(pm, -32767.0), 32767.0));
}

static void to_si(const struct epos4 *e, int32_t counts, int32_t velocity,
		  struct drive_sample *s)
{
	double rpm = velocity * e->rpm_per_unit;

	s->position = counts * e->d.units[0].si_per_count;
	s->velocity = rpm * e->counts_per_rev / 60.0 *
		      e->d.units[0].si_per_count;
}

static int read_fault(struct epos4 *e, struct drive_sample *s)
{
	uint32_t code = 0;
	int r = 0;

	s->fault = e->state == CANOPEN_FAULT ||
		   e->state == CANOPEN_FAULT_REACTION_ACTIVE;
	if (!s->fault) {
		e->fault_read = false;
	} else if (!e->fault_read) {
		r = read_object(e, CANOPEN_ERROR_CODE, &code);
		e->fault_code = code & 0xFFFF;
		e->fault_read = r == 0;
	}
	s->code = e->fault_code;
	return r;
}

/*
 * The tool's signals this drive reads, into S, after the digital inputs
 * INPUTS were read: the auxiliary encoder's counts and the analogue
 * input's millivolts, each one more request.
 */
static int read_tool(struct epos4 *e, uint32_t inputs, struct drive_sample *s)
{
	const struct config_epos4 *c = &e->cfg;
	uint32_t counts = 0, mv = 0;
	int r = 0;

	if (e->d.tool[0] & CONFIG_TOOL_DEPTH) {
		r = sdo(e, false, CANOPEN_ADDITIONAL_POSITION,
			(uint8_t)c->tool_depth_sensor, &counts);
	}
	if (!r && (e->d.tool[0] & CONFIG_TOOL_OPENING)) {
		r = sdo(e, false, EPOS4_ANALOG_INPUT_VOLTAGE,
			(uint8_t)c->tool_opening_input, &mv);
	}
	s->tool.depth_m = (int32_t)counts * c->tool_m_per_count +
			  c->tool_depth_offset_m;
	s->tool.opening = drive_tool_opening((int16_t)mv, c->tool_closed_mv,
					     c->tool_open_mv);
	s->tool.pedal = c->tool_pedal_bit >= 0 &&
			((inputs >> c->tool_pedal_bit) & 1u);
	return r;
}

static int epos4_exchange(struct drive *d, const double *setpoint,
			  struct drive_sample *s)
{
	struct epos4 *e = to_epos4(d);
	uint32_t pos, vel, sw, inputs = 0;
	int r = 0;

	if (e->enabled) {
		r = write_object(e, CANOPEN_TARGET_TORQUE,
				 (uint16_t)torque_permille(e, setpoint[0]));
	}
	r = r ? r : read_object(e, CANOPEN_POSITION_ACTUAL, &pos);
	r = r ? r : read_object(e, CANOPEN_VELOCITY_ACTUAL, &vel);
	r = r ? r : read_object(e, CANOPEN_STATUSWORD, &sw);
	if (!r && (d->valves[0] || (d->tool[0] & CONFIG_TOOL_PEDAL))) {
		r = read_object(e, CANOPEN_DIGITAL_INPUTS, &inputs);
	}
	r = r ? r : read_tool(e, inputs, s);
	if (r) {
		return r;
	}
	e->statusword = (uint16_t)sw;
	e->state = canopen_state(e->statusword);
	to_si(e, (int32_t)pos, (int32_t)vel, s);
	s->valves = drive_valves_of_inputs(inputs, e->cfg.valve_bit);
	s->enabled = e->state == CANOPEN_OPERATION_ENABLED;
	return read_fault(e, s);
}

/*
 * The drive's communication watchdog: a heartbeat consumer that faults the
 * drive (0x8130) when the daemon falls silent for watchdog_s, so that a
 * dead daemon leaves no torque on (docs/TECHNICIAN.md says what that
 * means on a real EPOS4 on USB).
 */
static int set_watchdog(struct epos4 *e)
{
	uint32_t hb = (uint32_t)CANOPEN_MASTER_NODE << 16 |
		      (uint32_t)lround(e->cfg.watchdog_s * 1e3);

	if (e->cfg.watchdog_s <= 0) {
		return 0;
	}
	return sdo(e, true, CANOPEN_HEARTBEAT_CONSUMER, 1, &hb);
}

static int set_mode(struct epos4 *e)
{
	uint32_t shown;
	int r = write_object(e, CANOPEN_TARGET_TORQUE, 0);

	r = r ? r : set_watchdog(e);

	r = r ? r : write_object(e, CANOPEN_MODE, CANOPEN_MODE_CST);
	r = r ? r : read_object(e, CANOPEN_MODE_DISPLAY, &shown);
	if (!r && (int8_t)shown != CANOPEN_MODE_CST) {
		return drive_fail(&e->d, 0, -EPROTO, "mode of operation is %d "
				  "after asking for %d (cyclic synchronous "
				  "torque)", (int8_t)shown, CANOPEN_MODE_CST);
	}
	return r;
}

static int epos4_bring_up(struct drive *d, int i)
{
	struct epos4 *e = to_epos4(d);
	uint16_t cw;
	int r;

	(void)i;
	if (e->up_step == 0) {
		r = set_mode(e);
		e->up_step = r ? 0 : 1;
		e->up_deadline_ns = mono_ns() + UP_TIMEOUT_NS;
		return r ? r : 1;
	}
	r = canopen_step_to_enabled(e->state, &cw);
	if (r == 0) {
		e->enabled = true;
		e->up_step = 0;
		return 0;
	}
	if (mono_ns() > e->up_deadline_ns) {
		e->up_step = 0;
		return drive_fail(d, 0, -ETIMEDOUT, "not in operation enabled "
				  "within %.0f s: %s (statusword 0x%04x)",
				  (double)UP_TIMEOUT_NS / ENDOSIM_NS_PER_S,
				  canopen_state_name(e->state), e->statusword);
	}
	r = r > 0 ? write_object(e, CANOPEN_CONTROLWORD, cw) : 0;
	return r ? r : 1;
}

static int epos4_bring_down(struct drive *d, int i)
{
	struct epos4 *e = to_epos4(d);
	int r1, r2, r3;

	(void)i;
	e->enabled = false;
	e->up_step = 0;
	r1 = write_object(e, CANOPEN_TARGET_TORQUE, 0);
	r2 = write_object(e, CANOPEN_CONTROLWORD, CANOPEN_CW_QUICK_STOP);
	r3 = write_object(e, CANOPEN_CONTROLWORD, CANOPEN_CW_DISABLE_VOLTAGE);
	return r1 ? r1 : r2 ? r2 : r3;
}

static int epos4_clear_fault(struct drive *d, int i)
{
	struct epos4 *e = to_epos4(d);
	int r;

	(void)i;
	e->fault_read = false;
	r = write_object(e, CANOPEN_CONTROLWORD, CANOPEN_CW_FAULT_RESET);
	return r ? r
		 : write_object(e, CANOPEN_CONTROLWORD,
				CANOPEN_CW_DISABLE_VOLTAGE);
}

static void epos4_destroy(struct drive *d)
{
	epos4_close(d);
	free(d);
}

static const char *epos4_describe_fault(uint32_t code)
{
	return canopen_error_text((uint16_t)code);
}

static const struct drive_ops epos4_ops = {
	.kind = "epos4-usb",
	.open = epos4_open,
	.bring_up = epos4_bring_up,
	.exchange = epos4_exchange,
	.bring_down = epos4_bring_down,
	.clear_fault = epos4_clear_fault,
	.close = epos4_close,
	.destroy = epos4_destroy,
	.describe_fault = epos4_describe_fault,
};

struct drive *drive_epos4_create(const struct config *cfg, int axis)
{
	struct epos4 *e = calloc(1, sizeof(*e));
	const struct config_epos4 *c = &cfg->epos4[axis];

	if (!e) {
		log_err("epos4-usb %s: out of memory", names_axis(axis));
		return NULL;
	}
	e->d.ops = &epos4_ops;
	e->d.n = 1;
	e->d.axis[0] = axis;
	drive_units_init(&e->d.units[0], cfg, axis);
	e->d.valves[0] = config_axis_valves(cfg, axis);
	e->d.tool[0] = config_axis_tool(cfg, axis);
	e->cfg = *c;
	e->counts_per_rev = cfg->axis[axis].counts_per_rev;
	e->timeout_ms = (unsigned int)lround(fmax(c->timeout_s * 1e3, 1.0));
	snprintf(e->d.name, sizeof(e->d.name), "epos4-usb %04x:%04x%s%s%s",
		 c->vid, c->pid, c->serial[0] ? " serial '" : "", c->serial,
		 c->serial[0] ? "'" : "");
	snprintf(e->d.unit[0], sizeof(e->d.unit[0]), "node %d", c->node_id);
	return &e->d;
}
