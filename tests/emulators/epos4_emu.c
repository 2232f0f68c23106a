/*
 * epos4_emu.c - maxon EPOS4 drives on USB, emulated with umockdev, so that
 * endosimd's unmodified libusb code talks to them at the usbfs ioctl level.
 *
 * How it runs: this program creates a umockdev testbed (a private /sys and
 * /dev under $TMPDIR) holding one USB device per --device, answers the usbfs
 * ioctls of each in umockdev's worker thread, and writes the testbed's
 * directory to --ready FILE (and stdout). The program under test is started
 * separately with
 *
 *     UMOCKDEV_DIR=$(cat FILE) LD_PRELOAD=libumockdev-preload.so.0 endosimd ...
 *
 * (the preload library redirects /sys and /dev/bus/usb into the testbed and
 * forwards the ioctls here; everything else passes through). Mind: the
 * client's ioctls block while this emulator is stopped, and the preload
 * library ends the client when the emulator dies: stop the client first.
 * A client that dies (even in the middle of an ioctl) leaves the emulator
 * running: its memory can no longer be read, and what it asked is dropped.
 * An unplug is emulated with the "unplug" command, never by killing this.
 *
 * Each device decodes the EPOS4 frame protocol (epos4_frame.h), answers
 * ReadObject/WriteObject from a small object dictionary, runs the CiA 402
 * state machine (canopen.h), and turns a motor (emu.h) with the commanded
 * torque in mode 10 plus a scripted hand.
 *
 * Control commands (one per line on --control FIFO), SERIAL naming a device:
 *   fault SERIAL [CODE] [sticky]  the drive faults with error CODE (0x603F,
 *                                 default 0x2310); sticky: fault reset does
 *                                 not clear it until "clear"
 *   clear SERIAL                  the cause of a sticky fault goes away
 *   error SERIAL [ABORT]          the next reply refuses with ABORT (default
 *                                 0x08000020)
 *   crc SERIAL                    the next reply has a wrong CRC
 *   unplug SERIAL / plug SERIAL   the device leaves the bus / comes back
 *   hand SERIAL TORQUE [HZ]       the hand's torque on the motor, N m (a
 *                                 sine of that amplitude at HZ)
 *   move SERIAL RPM               the hand turns the motor at RPM exactly
 *   place SERIAL COUNTS           the motor is put at COUNTS
 *   input SERIAL BIT on|off       bit BIT (0..31) of the digital inputs
 *                                 0x60FD is set / cleared: a switch wired
 *                                 to the drive (the handle's valves), as
 *                                 it stays through an unplug
 *   aux SERIAL SUB COUNTS         the additional position actual value
 *                                 0x60E4:SUB (2 or 3: the drive's sensor
 *                                 2 or 3, an auxiliary encoder; 1 is the
 *                                 motor's) reads COUNTS: the tool's depth
 *   analog SERIAL N MV            analogue input N (1 or 2) reads MV
 *                                 millivolts (0x3160:N): the tool's
 *                                 handle
 *   quit
 * The state file (--state) has one line per device: serial, present, CiA
 * 402 state, statusword, mode, target torque (per mille), torque applied
 * (N m), position (counts), velocity (rpm), requests served, the error
 * code 0x603F, the heartbeat consumer time (ms), the digital inputs, the
 * auxiliary sensors' counts and the analogue inputs' millivolts.
 *
 * Communication watchdog: with a heartbeat consumer time set in 0x1016:01
 * (low 16 bits, ms), a drive in operation enabled that receives no request
 * for that long faults with 0x8130 (life guard or heartbeat error) and
 * drops its torque. Every request counts as a heartbeat: over USB the
 * master's requests are the only sign of life the emulated drive sees.
 */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <glib-unix.h>
#include <glib.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
/* linux/ioctl.h first: usbdevice_fs.h needs it */
#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <umockdev.h>

#include "rig/canopen.h"
#include "rig/epos4_frame.h"
#include "emu.h"

#define MAX_DEV 4
#define REPLY_MAX 4096
#define TICK_MS 1
#define STATE_EVERY_S 0.02
#define DEFAULT_RATED_UNM 200000 /* 0.2 N m, in 0x6076 units (uN m) */
#define DEFAULT_FAULT 0x2310
#define DEFAULT_ABORT 0x08000020u

/* A URB and the client (one open of the device node) it belongs to. */
struct urb_ref {
	UMockdevIoctlClient *client;
	UMockdevIoctlData *urb;
};

struct dev {
	char serial[64];
	int node, devnum;
	char sysfs[64];      /* /sys/devices/... */
	char devnode[64];    /* /dev/bus/usb/001/NNN */
	UMockdevIoctlBase *handler;
	bool present;
	int fifo;            /* our end of the device node (a FIFO) */
	GList *ready;        /* struct urb_ref: URBs their clients may reap */
	struct urb_ref pending_in; /* an IN transfer waiting for a reply */
	uint8_t reply[REPLY_MAX];
	size_t reply_len;
	struct epos4_decoder dec;
	/* the drive */
	enum canopen_state state;
	uint16_t cw;
	int8_t mode;
	int16_t target;      /* per mille of rated */
	uint16_t max_torque; /* per mille of rated */
	uint32_t rated;      /* uN m */
	uint16_t error;
	bool sticky;
	uint32_t heartbeat;  /* 0x1016:01, low 16 bits: ms; 0: off */
	uint32_t inputs;     /* digital inputs 0x60FD */
	int32_t aux[2];      /* 0x60E4:02, :03: sensors 2 and 3, counts */
	int16_t analog_mv[2]; /* 0x3160:01, :02 */
	double last_request_s;
	uint32_t inject_abort;
	bool inject_crc;
	struct emu_motor motor;
	unsigned long long requests;
};

struct emu {
	UMockdevTestbed *tb;
	char *root;
	GMutex lock;
	struct dev dev[MAX_DEV];
	int n;
	int vid, pid, cpr;
	FILE *trace;
	const char *state_path;
	int ctl;
	struct emu_lines lines;
	GMainLoop *loop;
	double last_s, last_state_s;
};

/* --- the drive ------------------------------------------------------ */

static uint16_t statusword(const struct dev *d)
{
	uint16_t sw = canopen_statusword(d->state) | 0x0200; /* remote */

	if (d->state >= CANOPEN_READY_TO_SWITCH_ON &&
	    d->state <= CANOPEN_QUICK_STOP_ACTIVE) {
		sw |= 0x0010; /* voltage enabled */
	}
	return sw;
}

static void power_up(struct dev *d)
{
	d->state = d->sticky ? CANOPEN_FAULT : CANOPEN_SWITCH_ON_DISABLED;
	d->cw = 0;
	d->mode = 0;
	d->target = 0;
	d->max_torque = 1000;
	d->heartbeat = 0;
	d->inject_abort = 0;
	d->inject_crc = false;
	epos4_decoder_reset(&d->dec);
	d->reply_len = 0;
}

/* CiA 402: the device side of the controlword. */
static void controlword(struct dev *d, uint16_t cw)
{
	bool reset_edge = (cw & 0x80) && !(d->cw & 0x80);
	enum canopen_state s = d->state;

	d->cw = cw;
	if (s == CANOPEN_FAULT) {
		if (reset_edge && !d->sticky) {
			d->state = CANOPEN_SWITCH_ON_DISABLED;
			d->error = 0;
		}
		return;
	}
	if (cw & 0x80) {
		return;
	}
	if (!(cw & 0x02)) { /* disable voltage */
		d->state = CANOPEN_SWITCH_ON_DISABLED;
	} else if (!(cw & 0x04)) { /* quick stop */
		d->state = s == CANOPEN_OPERATION_ENABLED
				   ? CANOPEN_QUICK_STOP_ACTIVE
				   : CANOPEN_SWITCH_ON_DISABLED;
	} else if (!(cw & 0x01)) { /* shutdown */
		d->state = s == CANOPEN_QUICK_STOP_ACTIVE ? s
			   : CANOPEN_READY_TO_SWITCH_ON;
	} else if (!(cw & 0x08)) { /* switch on, disable operation */
		d->state = s == CANOPEN_READY_TO_SWITCH_ON ||
					   s == CANOPEN_OPERATION_ENABLED
				   ? CANOPEN_SWITCHED_ON : s;
	} else if (s == CANOPEN_SWITCHED_ON || s == CANOPEN_QUICK_STOP_ACTIVE) {
		d->state = CANOPEN_OPERATION_ENABLED;
	}
}

static double drive_torque_nm(const struct dev *d)
{
	int pm = d->target;

	if (d->state != CANOPEN_OPERATION_ENABLED ||
	    d->mode != CANOPEN_MODE_CST) {
		return 0.0;
	}
	pm = pm > d->max_torque ? d->max_torque : pm;
	pm = pm < -d->max_torque ? -d->max_torque : pm;
	return pm * (d->rated * 1e-6) / 1000.0;
}

static int32_t counts(const struct emu *e, const struct dev *d)
{
	return (int32_t)lround(d->motor.plant.x * e->cpr / (2.0 * M_PI));
}

static int32_t rpm(const struct dev *d)
{
	return (int32_t)lround(d->motor.plant.v * 60.0 / (2.0 * M_PI));
}

/* ReadObject of the sensors 0x60E4 and the analogue inputs 0x3160. */
static uint32_t od_read_sensor(struct emu *e, struct dev *d, uint16_t index,
			       uint8_t sub, uint32_t *value)
{
	if (index == CANOPEN_ADDITIONAL_POSITION) {
		*value = sub == 0 ? 3 : sub == 1 ? (uint32_t)counts(e, d)
					: (uint32_t)d->aux[(sub - 2) & 1];
		return sub <= 3 ? 0 : 0x06090011;
	}
	*value = sub == 0 ? 2 : (uint16_t)d->analog_mv[(sub - 1) & 1];
	return sub <= 2 ? 0 : 0x06090011;
}

/* ReadObject: the abort code, VALUE set on success. */
static uint32_t od_read(struct emu *e, struct dev *d, uint16_t index,
			uint8_t sub, uint32_t *value)
{
	if (index == CANOPEN_ADDITIONAL_POSITION ||
	    index == EPOS4_ANALOG_INPUT_VOLTAGE) {
		return od_read_sensor(e, d, index, sub, value);
	}
	if (sub != 0 && index != 0x1018 && index != CANOPEN_HEARTBEAT_CONSUMER) {
		return 0x06090011;
	}
	switch (index) {
	case CANOPEN_DEVICE_TYPE: *value = 0x00020192; return 0;
	case CANOPEN_HEARTBEAT_CONSUMER:
		*value = sub == 0 ? 1 : d->heartbeat;
		return sub <= 1 ? 0 : 0x06090011;
	case 0x1018: /* identity: vendor, product, revision, serial */
		*value = sub == 1 ? 0xFB : sub == 2 ? 0x0640 : sub == 4 ? 1 : 0;
		return sub >= 1 && sub <= 4 ? 0 : 0x06090011;
	case CANOPEN_ERROR_CODE: *value = d->error; return 0;
	case CANOPEN_CONTROLWORD: *value = d->cw; return 0;
	case CANOPEN_STATUSWORD: *value = statusword(d); return 0;
	case CANOPEN_MODE:
	case CANOPEN_MODE_DISPLAY: *value = (uint8_t)d->mode; return 0;
	case CANOPEN_POSITION_ACTUAL: *value = (uint32_t)counts(e, d); return 0;
	case CANOPEN_VELOCITY_ACTUAL: *value = (uint32_t)rpm(d); return 0;
	case CANOPEN_TARGET_TORQUE: *value = (uint16_t)d->target; return 0;
	case CANOPEN_MAX_TORQUE: *value = d->max_torque; return 0;
	case CANOPEN_RATED_TORQUE: *value = d->rated; return 0;
	case CANOPEN_TORQUE_ACTUAL:
		*value = (uint16_t)(int16_t)lround(drive_torque_nm(d) /
						   (d->rated * 1e-9));
		return 0;
	case CANOPEN_SI_UNIT_VELOCITY: *value = CANOPEN_SI_UNIT_RPM; return 0;
	case CANOPEN_DIGITAL_INPUTS: *value = d->inputs; return 0;
	default: return 0x06020000;
	}
}

static bool valid_mode(int8_t m)
{
	return m == 1 || m == 3 || m == 6 || m == 8 || m == 9 || m == 10;
}

/* WriteObject: the abort code. */
static uint32_t od_write(struct dev *d, uint16_t index, uint8_t sub,
			 uint32_t value)
{
	if (index == CANOPEN_HEARTBEAT_CONSUMER && sub == 1) {
		d->heartbeat = value;
		return 0;
	}
	if (sub != 0) {
		return index == 0x1018 ? 0x06010002 : 0x06090011;
	}
	switch (index) {
	case CANOPEN_CONTROLWORD: controlword(d, (uint16_t)value); return 0;
	case CANOPEN_MODE:
		if (!valid_mode((int8_t)value)) {
			return 0x06090030;
		}
		d->mode = (int8_t)value;
		return 0;
	case CANOPEN_TARGET_TORQUE: d->target = (int16_t)value; return 0;
	case CANOPEN_MAX_TORQUE: d->max_torque = (uint16_t)value; return 0;
	case CANOPEN_RATED_TORQUE: d->rated = value; return 0;
	case CANOPEN_QUICK_STOP_OPTION: return 0;
	case CANOPEN_DEVICE_TYPE: case 0x1018: case CANOPEN_ERROR_CODE:
	case CANOPEN_STATUSWORD: case CANOPEN_MODE_DISPLAY:
	case CANOPEN_POSITION_ACTUAL: case CANOPEN_VELOCITY_ACTUAL:
	case CANOPEN_TORQUE_ACTUAL: case CANOPEN_SI_UNIT_VELOCITY:
	case CANOPEN_DIGITAL_INPUTS: case CANOPEN_ADDITIONAL_POSITION:
	case EPOS4_ANALOG_INPUT_VOLTAGE:
		return 0x06010002;
	default: return 0x06020000;
	}
}

/* Answers one request frame into RSP; NOTE says what it was. */
static void serve(struct emu *e, struct dev *d, const struct epos4_frame *req,
		  struct epos4_frame *rsp, char *note, size_t size)
{
	uint8_t op, node, sub;
	uint16_t index;
	uint32_t value, abort;

	if (epos4_parse_request(req, &op, &node, &index, &sub, &value)) {
		epos4_response(rsp, 0x05040001, false, 0);
		snprintf(note, size, "opcode 0x%02x: unknown", req->opcode);
		return;
	}
	d->requests++;
	d->last_request_s = emu_now_s();
	if (node != d->node && node != 0) {
		abort = 0x06020000;
	} else if (op == EPOS4_OP_READ_OBJECT) {
		abort = od_read(e, d, index, sub, &value);
	} else {
		abort = od_write(d, index, sub, value);
	}
	if (d->inject_abort) {
		abort = d->inject_abort;
		d->inject_abort = 0;
	}
	epos4_response(rsp, abort, op == EPOS4_OP_READ_OBJECT, abort ? 0 : value);
	snprintf(note, size, "%s node %u 0x%04x/%02x %s 0x%08x, abort 0x%08x",
		 op == EPOS4_OP_READ_OBJECT ? "ReadObject" : "WriteObject",
		 node, index, sub, op == EPOS4_OP_READ_OBJECT ? "->" : "=",
		 value, abort);
}

/* Queues the encoded RSP for the next IN transfers. */
static void queue_reply(struct emu *e, struct dev *d,
			const struct epos4_frame *rsp, const char *note)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	size_t n = epos4_frame_encode(rsp, buf, sizeof(buf));
	char tag[80];

	if (d->inject_crc && n >= 2) {
		buf[n - 1] ^= 0x5A; /* a DLE here would need stuffing: none */
		if (buf[n - 1] == EPOS4_DLE || buf[n - 2] == EPOS4_DLE) {
			buf[n - 1] ^= 0x01;
		}
		d->inject_crc = false;
	}
	if (d->reply_len + n <= sizeof(d->reply)) {
		memcpy(d->reply + d->reply_len, buf, n);
		d->reply_len += n;
	}
	snprintf(tag, sizeof(tag), "%s >", d->serial);
	emu_trace(e->trace, tag, buf, n, note);
}

static void receive(struct emu *e, struct dev *d, const uint8_t *p, size_t n)
{
	struct epos4_frame req, rsp;
	char note[160], tag[80];

	snprintf(tag, sizeof(tag), "%s <", d->serial);
	emu_trace(e->trace, tag, p, n, NULL);
	for (size_t i = 0; i < n; i++) {
		int r = epos4_decoder_feed(&d->dec, p[i], &req);

		if (r > 0) {
			serve(e, d, &req, &rsp, note, sizeof(note));
			queue_reply(e, d, &rsp, note);
		} else if (r == -EBADMSG) {
			epos4_response(&rsp, 0x05040004, false, 0);
			queue_reply(e, d, &rsp, "request CRC error");
		}
	}
}

/* --- usbfs ---------------------------------------------------------- */

static void fifo_fill(struct dev *d)
{
	char page[4096] = { 0 };

	while (write(d->fifo, page, sizeof(page)) > 0) {
	}
}

static void fifo_drain(struct dev *d)
{
	char buf[65536];

	while (read(d->fifo, buf, sizeof(buf)) > 0) {
	}
}

/* The URB may be reaped: its client's poll() sees the FIFO writable. */
static void make_ready(struct dev *d, UMockdevIoctlClient *client,
		       UMockdevIoctlData *urb)
{
	struct urb_ref *r = g_new(struct urb_ref, 1);

	r->client = g_object_ref(client);
	r->urb = urb;
	d->ready = g_list_append(d->ready, r);
	fifo_drain(d);
}

static void drop_ref(struct urb_ref *r)
{
	g_object_unref(r->urb);
	g_object_unref(r->client);
	g_free(r);
}

/* Forgets the URBs of clients that closed the device meanwhile. */
static void purge(struct dev *d)
{
	GList *next;

	for (GList *l = d->ready; l; l = next) {
		struct urb_ref *r = l->data;

		next = l->next;
		if (!umockdev_ioctl_client_get_connected(r->client)) {
			drop_ref(r);
			d->ready = g_list_delete_link(d->ready, l);
		}
	}
}

static struct usbdevfs_urb *urb_of(UMockdevIoctlData *data)
{
	return (struct usbdevfs_urb *)data->data;
}

static void complete_urb(UMockdevIoctlData *urb, int status, int length)
{
	struct usbdevfs_urb *u = urb_of(urb);

	u->status = status;
	u->actual_length = length;
	umockdev_ioctl_data_update(urb, 0, urb->data, urb->data_len);
}

/* Ends the pending IN transfer with STATUS and LENGTH bytes. */
static void finish_in(struct dev *d, int status, int length)
{
	complete_urb(d->pending_in.urb, status, length);
	make_ready(d, d->pending_in.client, d->pending_in.urb);
	g_object_unref(d->pending_in.client);
	d->pending_in = (struct urb_ref){ 0 };
}

/* The URB's buffer in the client; NULL when the client is gone. */
static UMockdevIoctlData *urb_buffer(UMockdevIoctlData *urb)
{
	return umockdev_ioctl_data_resolve(
		urb, G_STRUCT_OFFSET(struct usbdevfs_urb, buffer),
		(gsize)urb_of(urb)->buffer_length, NULL);
}

/* Copies waiting reply bytes into the pending IN URB. */
static void feed_in(struct dev *d)
{
	UMockdevIoctlData *urb = d->pending_in.urb, *buf;
	size_t n;

	if (!urb || !d->reply_len) {
		return;
	}
	n = (size_t)urb_of(urb)->buffer_length;
	n = n < d->reply_len ? n : d->reply_len;
	buf = urb_buffer(urb);
	if (!buf) { /* its client died: the transfer dies with it */
		g_object_unref(urb);
		g_object_unref(d->pending_in.client);
		d->pending_in = (struct urb_ref){ 0 };
		return;
	}
	umockdev_ioctl_data_update(buf, 0, d->reply, (gint)n);
	g_object_unref(buf);
	memmove(d->reply, d->reply + n, d->reply_len - n);
	d->reply_len -= n;
	finish_in(d, 0, (int)n);
}

/* A string descriptor: 0 the languages, then the strings. */
static size_t string_descriptor(const struct dev *d, int index, uint8_t *out)
{
	const char *s = index == 1 ? "maxon motor ag" : index == 2 ? "EPOS4"
			: index == 3 ? d->serial : NULL;
	size_t n = 2;

	out[1] = 3;
	if (index == 0) {
		out[2] = 0x09;
		out[3] = 0x04;
		n = 4;
	}
	for (size_t i = 0; s && s[i] && n + 2 <= 254; i++) {
		out[n++] = (uint8_t)s[i];
		out[n++] = 0;
	}
	out[0] = (uint8_t)n;
	return n;
}

static void control_urb(struct dev *d, UMockdevIoctlClient *client,
			UMockdevIoctlData *urb)
{
	UMockdevIoctlData *buf = urb_buffer(urb);
	const uint8_t *setup;
	uint8_t desc[256];
	size_t n, want;

	if (!buf) {
		g_object_unref(urb);
		return;
	}
	setup = buf->data;
	want = (size_t)(setup[6] | setup[7] << 8);

	if (setup[0] == 0x80 && setup[1] == 6 && setup[3] == 3) {
		n = string_descriptor(d, setup[2], desc);
		n = n < want ? n : want;
		umockdev_ioctl_data_update(buf, 8, desc, (gint)n);
		complete_urb(urb, 0, (int)n);
	} else {
		complete_urb(urb, -EPIPE, 0);
	}
	g_object_unref(buf);
	make_ready(d, client, urb);
}

static void submit(struct emu *e, struct dev *d, UMockdevIoctlClient *client,
		   UMockdevIoctlData *urb)
{
	struct usbdevfs_urb *u = urb_of(urb);
	UMockdevIoctlData *buf;

	if (u->type == USBDEVFS_URB_TYPE_CONTROL) {
		control_urb(d, client, urb);
	} else if ((u->endpoint & 0x80) && d->pending_in.urb) {
		complete_urb(urb, -EBUSY, 0); /* one reader at a time */
		make_ready(d, client, urb);
	} else if (u->endpoint & 0x80) {
		d->pending_in = (struct urb_ref){ g_object_ref(client), urb };
		feed_in(d);
	} else if (!(buf = urb_buffer(urb))) {
		g_object_unref(urb);
	} else {
		receive(e, d, buf->data, (size_t)u->buffer_length);
		g_object_unref(buf);
		complete_urb(urb, 0, u->buffer_length);
		make_ready(d, client, urb);
		feed_in(d);
	}
}

static void reap(struct dev *d, UMockdevIoctlClient *client,
		 UMockdevIoctlData *arg)
{
	UMockdevIoctlData *slot;
	struct urb_ref *r = NULL;
	GList *l;

	purge(d);
	for (l = d->ready; l && !r; l = l->next) {
		r = ((struct urb_ref *)l->data)->client == client ? l->data
								  : NULL;
	}
	if (!r) {
		umockdev_ioctl_client_complete(client, -1,
					       d->present ? EAGAIN : ENODEV);
		return;
	}
	d->ready = g_list_remove(d->ready, r);
	slot = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), NULL);
	if (!slot) {
		drop_ref(r);
		umockdev_ioctl_client_complete(client, -1, ENODEV);
		return;
	}
	umockdev_ioctl_data_set_ptr(slot, 0, r->urb);
	g_object_unref(slot);
	drop_ref(r);
	if (!d->ready) {
		fifo_fill(d);
	}
	umockdev_ioctl_client_complete(client, 0, 0);
}

static void discard(struct dev *d, UMockdevIoctlClient *client)
{
	if (d->pending_in.client != client) {
		umockdev_ioctl_client_complete(client, -1, EINVAL);
		return;
	}
	finish_in(d, -ENOENT, 0);
	umockdev_ioctl_client_complete(client, 0, 0);
}

struct handler_ctx {
	struct emu *e;
	struct dev *d;
};

static void capabilities(UMockdevIoctlClient *client, UMockdevIoctlData *arg)
{
	UMockdevIoctlData *c = umockdev_ioctl_data_resolve(arg, 0, 4, NULL);
	guint32 caps = USBDEVFS_CAP_BULK_CONTINUATION |
		       USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
		       USBDEVFS_CAP_REAP_AFTER_DISCONNECT |
		       USBDEVFS_CAP_ZERO_PACKET;

	if (!c) {
		umockdev_ioctl_client_complete(client, -1, ENODEV);
		return;
	}
	umockdev_ioctl_data_update(c, 0, (guint8 *)&caps, sizeof(caps));
	g_object_unref(c);
	umockdev_ioctl_client_complete(client, 0, 0);
}

static void dispatch(struct emu *e, struct dev *d, UMockdevIoctlClient *client,
		     gulong request, UMockdevIoctlData *arg)
{
	UMockdevIoctlData *urb;

	switch (request) {
	case USBDEVFS_GET_CAPABILITIES:
		capabilities(client, arg);
		break;
	case USBDEVFS_SUBMITURB:
		urb = umockdev_ioctl_data_resolve(arg, 0,
						  sizeof(struct usbdevfs_urb),
						  NULL);
		if (!urb) { /* the client died: nothing to submit */
			umockdev_ioctl_client_complete(client, -1, ENODEV);
			break;
		}
		submit(e, d, client, urb);
		umockdev_ioctl_client_complete(client, 0, 0);
		break;
	case USBDEVFS_REAPURB:
	case USBDEVFS_REAPURBNDELAY:
		reap(d, client, arg);
		break;
	case USBDEVFS_DISCARDURB:
		discard(d, client);
		break;
	default: /* claim, release, set interface, clear halt, reset */
		umockdev_ioctl_client_complete(client, 0, 0);
		break;
	}
}

static gboolean on_ioctl(UMockdevIoctlBase *handler,
			 UMockdevIoctlClient *client, gpointer data)
{
	struct handler_ctx *hc = data;
	gulong request = umockdev_ioctl_client_get_request(client);
	UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);

	(void)handler;
	g_mutex_lock(&hc->e->lock);
	if (!hc->d->present && request != USBDEVFS_REAPURB &&
	    request != USBDEVFS_REAPURBNDELAY) {
		umockdev_ioctl_client_complete(client, -1, ENODEV);
	} else {
		dispatch(hc->e, hc->d, client, request, arg);
	}
	g_mutex_unlock(&hc->e->lock);
	return TRUE;
}

/* --- plugging --------------------------------------------------------- */

/* Device, configuration, interface (vendor class) and two bulk endpoints. */
static char *descriptors(const struct emu *e)
{
	return g_strdup_printf("1201000200000040%02x%02x%02x%02x000101020301"
			       "0902200001010080320904000002ff000000"
			       "0705010240000007058102400000",
			       e->vid & 0xFF, e->vid >> 8, e->pid & 0xFF,
			       e->pid >> 8);
}

static char *device_record(const struct emu *e, const struct dev *d)
{
	char *hex = descriptors(e);
	char *rec = g_strdup_printf(
		"P: %s\nN: bus/usb/001/%03d\nE: SUBSYSTEM=usb\nE: DRIVER=usb\n"
		"E: BUSNUM=001\nE: DEVNUM=%03d\nE: DEVNAME=%s\n"
		"E: DEVTYPE=usb_device\nA: bConfigurationValue=1\\n\n"
		"A: busnum=1\\n\nA: devnum=%d\\n\nA: speed=12\\n\n"
		"H: descriptors=%s\n",
		d->sysfs + strlen("/sys"), d->devnum, d->devnum, d->devnode,
		d->devnum, hex);

	g_free(hex);
	return rec;
}

/* Replaces the device node by a FIFO kept full: see DEVICE-EMULATION. */
static int node_fifo(struct emu *e, struct dev *d)
{
	char *path = g_strdup_printf("%s%s", e->root, d->devnode);

	unlink(path);
	if (d->fifo >= 0) {
		close(d->fifo);
	}
	d->fifo = mkfifo(path, 0666) < 0
			  ? -1 : open(path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
	g_free(path);
	if (d->fifo < 0) {
		return -1;
	}
	fifo_fill(d);
	return 0;
}

static int plug(struct emu *e, struct dev *d)
{
	char *rec = device_record(e, d);
	GError *err = NULL;
	int r = 0;

	if (!umockdev_testbed_add_from_string(e->tb, rec, &err)) {
		fprintf(stderr, "epos4-emu: %s: cannot plug in: %s\n",
			d->serial, err ? err->message : "?");
		g_clear_error(&err);
		r = -1;
	}
	g_free(rec);
	g_mutex_lock(&e->lock);
	if (!r && node_fifo(e, d)) {
		fprintf(stderr, "epos4-emu: %s: device node: %s\n", d->serial,
			strerror(errno));
		r = -1;
	}
	power_up(d);
	d->present = r == 0;
	g_mutex_unlock(&e->lock);
	return r;
}

static void unplug(struct emu *e, struct dev *d)
{
	g_mutex_lock(&e->lock);
	if (!d->present) {
		g_mutex_unlock(&e->lock);
		return;
	}
	d->present = false;
	if (d->pending_in.urb) {
		/* in flight: -ESHUTDOWN, then ENODEV for everything */
		finish_in(d, -ESHUTDOWN, 0);
	}
	d->reply_len = 0;
	g_mutex_unlock(&e->lock);
	/* the ioctl handler stays: a client's fd gets ENODEV, not EOF */
	umockdev_testbed_remove_device(e->tb, d->sysfs);
}

/* --- control and time ------------------------------------------------- */

static struct dev *find(struct emu *e, const char *serial)
{
	for (int i = 0; i < e->n; i++) {
		if (!strcmp(e->dev[i].serial, serial)) {
			return &e->dev[i];
		}
	}
	return NULL;
}

static unsigned long number(const char *s, unsigned long def)
{
	return s ? strtoul(s, NULL, 0) : def;
}

static void inject_fault(struct dev *d, int argc, char **argv)
{
	d->error = (uint16_t)number(argc > 2 ? argv[2] : NULL, DEFAULT_FAULT);
	d->sticky = argc > 3 && !strcmp(argv[3], "sticky");
	d->state = CANOPEN_FAULT;
}

static void set_input(struct dev *d, int bit, bool on)
{
	d->inputs = on ? d->inputs | 1u << bit : d->inputs & ~(1u << bit);
}

/* A command that changes a device's drive or motor; under the lock. */
static void change(struct emu *e, struct dev *d, int n, char **w,
		   const char *args)
{
	if (!strcmp(w[0], "fault")) {
		inject_fault(d, n, w);
	} else if (!strcmp(w[0], "clear")) {
		d->sticky = false;
	} else if (!strcmp(w[0], "error")) {
		d->inject_abort = (uint32_t)number(n > 2 ? w[2] : NULL,
						   DEFAULT_ABORT);
	} else if (!strcmp(w[0], "crc")) {
		d->inject_crc = true;
	} else if (!strcmp(w[0], "hand") && n >= 3) {
		emu_motor_hand(&d->motor, args);
	} else if (!strcmp(w[0], "move") && n >= 3) {
		d->motor.moving = true;
		d->motor.move_rad_s = atof(w[2]) * 2.0 * M_PI / 60.0;
		d->motor.plant.v = d->motor.move_rad_s; /* from now on */
	} else if (!strcmp(w[0], "place") && n >= 3) {
		d->motor.plant.x = atof(w[2]) * 2.0 * M_PI / e->cpr;
	} else if (!strcmp(w[0], "input") && n >= 4 && atoi(w[2]) >= 0 &&
		   atoi(w[2]) < 32) {
		set_input(d, atoi(w[2]), !strcmp(w[3], "on"));
	} else if (!strcmp(w[0], "aux") && n >= 4 && (atoi(w[2]) == 2 ||
						      atoi(w[2]) == 3)) {
		d->aux[atoi(w[2]) - 2] = (int32_t)atol(w[3]);
	} else if (!strcmp(w[0], "analog") && n >= 4 && (atoi(w[2]) == 1 ||
							 atoi(w[2]) == 2)) {
		d->analog_mv[atoi(w[2]) - 1] = (int16_t)atoi(w[3]);
	} else {
		fprintf(stderr, "epos4-emu: '%s': unknown command\n", w[0]);
	}
}

static void command(void *ctx, char *line)
{
	struct emu *e = ctx;
	char copy[512], *w[6];
	struct dev *d;
	int n;

	snprintf(copy, sizeof(copy), "%s", line);
	emu_trace(e->trace, "control", NULL, 0, copy);
	n = emu_words(line, w, 6);
	if (n == 1 && !strcmp(w[0], "quit")) {
		g_main_loop_quit(e->loop);
		return;
	}
	d = n >= 2 ? find(e, w[1]) : NULL;
	if (!d) {
		fprintf(stderr, "epos4-emu: '%s': no such device\n", copy);
	} else if (!strcmp(w[0], "unplug")) {
		unplug(e, d);
	} else if (!strcmp(w[0], "plug")) {
		if (!d->present) {
			plug(e, d);
		}
	} else {
		g_mutex_lock(&e->lock);
		change(e, d, n, w, n >= 3 ? copy + (w[2] - line) : "");
		g_mutex_unlock(&e->lock);
	}
}

static void write_state(struct emu *e)
{
	GString *s = g_string_new(NULL);

	for (int i = 0; i < e->n; i++) {
		const struct dev *d = &e->dev[i];
		char *state = g_strdup(canopen_state_name(d->state));

		g_strdelimit(state, " ", '_');
		g_string_append_printf(
			s, "serial=%s present=%d state=%s sw=0x%04x mode=%d "
			"target_permille=%d torque_nm=%.9g counts=%d rpm=%d "
			"requests=%llu error=0x%04x heartbeat_ms=%u "
			"inputs=0x%08x aux=%d,%d analog_mv=%d,%d\n",
			d->serial, d->present, state, statusword(d), d->mode,
			d->target, drive_torque_nm(d), counts(e, d), rpm(d),
			d->requests, d->error, d->heartbeat & 0xFFFF,
			d->inputs, d->aux[0], d->aux[1], d->analog_mv[0],
			d->analog_mv[1]);
		g_free(state);
	}
	emu_state_write(e->state_path, s->str);
	g_string_free(s, TRUE);
}

/* The drive's own watchdog: silence while enabled is a fault. */
static void watchdog(struct dev *d, double now)
{
	double limit_s = (d->heartbeat & 0xFFFF) / 1e3;

	if (d->present && limit_s > 0 && d->state == CANOPEN_OPERATION_ENABLED &&
	    now - d->last_request_s > limit_s) {
		d->error = CANOPEN_ERROR_HEARTBEAT;
		d->state = CANOPEN_FAULT;
	}
}

static gboolean tick(gpointer data)
{
	struct emu *e = data;
	double now = emu_now_s();

	emu_control_poll(e->ctl, &e->lines, command, e);
	g_mutex_lock(&e->lock);
	for (int i = 0; i < e->n; i++) {
		struct dev *d = &e->dev[i];

		watchdog(d, now);
		d->motor.drive_nm = drive_torque_nm(d);
		emu_motor_advance(&d->motor, now - e->last_s);
	}
	e->last_s = now;
	if (e->state_path && now - e->last_state_s >= STATE_EVERY_S) {
		write_state(e);
		e->last_state_s = now;
	}
	g_mutex_unlock(&e->lock);
	return G_SOURCE_CONTINUE;
}

static gboolean on_signal(gpointer data)
{
	g_main_loop_quit(((struct emu *)data)->loop);
	return G_SOURCE_REMOVE;
}

/* --- start-up --------------------------------------------------------- */

static void usage(void)
{
	fprintf(stderr,
		"usage: epos4-emu [options] --device SERIAL [--device SERIAL...]\n"
		"  --device SERIAL     one EPOS4 with this USB serial number\n"
		"  --vid N --pid N     USB ids (default 0x24e7:0x3b01)\n"
		"  --node N            node-ID (default 1)\n"
		"  --cpr N             encoder counts per motor turn (2048)\n"
		"  --rated UNM         rated torque 0x6076, uN m (200000)\n"
		"  -o inertia=|viscous=|coulomb=|hold=VALUE   the motor, SI\n"
		"  --ready FILE        write the testbed dir (UMOCKDEV_DIR) here\n"
		"  --control FIFO      commands (see the source's head)\n"
		"  --state FILE        what the devices see, rewritten ~50/s\n"
		"  --trace FILE        every frame in hex\n");
}

struct options {
	const char *ready, *control, *state, *trace;
	int node;
	uint32_t rated;
	struct emu_motor_params motor;
};

static int parse(int argc, char **argv, struct emu *e, struct options *o)
{
	static const struct option opts[] = {
		{ "device", required_argument, NULL, 'd' },
		{ "vid", required_argument, NULL, 'v' },
		{ "pid", required_argument, NULL, 'p' },
		{ "node", required_argument, NULL, 'n' },
		{ "cpr", required_argument, NULL, 'c' },
		{ "rated", required_argument, NULL, 'r' },
		{ "ready", required_argument, NULL, 'R' },
		{ "control", required_argument, NULL, 'C' },
		{ "state", required_argument, NULL, 'S' },
		{ "trace", required_argument, NULL, 'T' },
		{ NULL, 0, NULL, 0 },
	};
	int c;

	while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
		switch (c) {
		case 'd':
			if (e->n == MAX_DEV) {
				return -1;
			}
			snprintf(e->dev[e->n++].serial, 64, "%s", optarg);
			break;
		case 'v': e->vid = (int)strtol(optarg, NULL, 0); break;
		case 'p': e->pid = (int)strtol(optarg, NULL, 0); break;
		case 'n': o->node = atoi(optarg); break;
		case 'c': e->cpr = atoi(optarg); break;
		case 'r': o->rated = (uint32_t)strtoul(optarg, NULL, 0); break;
		case 'R': o->ready = optarg; break;
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
	return e->n && optind == argc && e->cpr > 0 ? 0 : -1;
}

static int setup(struct emu *e, const struct options *o)
{
	static struct handler_ctx hc[MAX_DEV];

	e->tb = umockdev_testbed_new();
	e->root = umockdev_testbed_get_root_dir(e->tb);
	for (int i = 0; i < e->n; i++) {
		struct dev *d = &e->dev[i];

		d->node = o->node;
		d->rated = o->rated;
		d->devnum = i + 2;
		d->fifo = -1;
		snprintf(d->sysfs, sizeof(d->sysfs), "/sys/devices/usb1/1-%d",
			 i + 1);
		snprintf(d->devnode, sizeof(d->devnode),
			 "/dev/bus/usb/001/%03d", d->devnum);
		emu_motor_init(&d->motor, &o->motor);
		hc[i] = (struct handler_ctx){ .e = e, .d = d };
		d->handler = umockdev_ioctl_base_new();
		g_signal_connect(d->handler, "handle-ioctl",
				 G_CALLBACK(on_ioctl), &hc[i]);
		if (!umockdev_testbed_attach_ioctl(e->tb, d->devnode,
						   d->handler, NULL) ||
		    plug(e, d)) {
			return -1;
		}
	}
	return 0;
}

static void announce(const struct emu *e, const char *ready)
{
	FILE *f;

	printf("%s\n", e->root);
	fflush(stdout);
	if (!ready) {
		return;
	}
	f = fopen(ready, "w");
	if (f) {
		fprintf(f, "%s\n", e->root);
		fclose(f);
	}
}

int main(int argc, char **argv)
{
	static struct emu e = { .vid = 0x24E7, .pid = 0x3B01, .cpr = 2048 };
	struct options o = { .node = 1, .rated = DEFAULT_RATED_UNM,
			     .motor = EMU_MOTOR_DEFAULTS };

	if (parse(argc, argv, &e, &o)) {
		usage();
		return 2;
	}
	g_mutex_init(&e.lock);
	e.ctl = o.control ? emu_control_open(o.control) : -1;
	e.trace = o.trace ? fopen(o.trace, "w") : NULL;
	e.state_path = o.state;
	if (setup(&e, &o)) {
		return 1;
	}
	e.loop = g_main_loop_new(NULL, FALSE);
	e.last_s = emu_now_s();
	g_timeout_add(TICK_MS, tick, &e);
	g_unix_signal_add(SIGTERM, on_signal, &e);
	g_unix_signal_add(SIGINT, on_signal, &e);
	announce(&e, o.ready);
	g_main_loop_run(e.loop);
	g_object_unref(e.tb); /* removes the testbed directory */
	return 0;
}
