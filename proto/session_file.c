/* session_file.c - the training session file (session_file.h). */
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "proto/session_file.h"

#include "proto/fields.h"

#define FRAME_OVERHEAD 12u /* type, length, crc */

void session_record_from_state(const struct endosim_state *in,
			       struct session_record *out)
{
	memset(out, 0, sizeof(*out));
	fields_to_record(&fields_status, in, out);
}

/* No tool, as the model publishes it: nothing held. */
static void no_tool(struct endosim_tool_state *t)
{
	t->captured = -1;
	t->event_polyp = -1;
}

/* The disabled patient's state, as the model publishes it. */
static void no_patient(struct endosim_patient_state *p)
{
	p->hand_site = -1;
	p->burst_segment = -1;
	p->pain_place = -1;
	p->torn_segment = -1;
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		p->factor[i] = 1;
	}
}

void session_record_to_state(const struct session_record *in,
			     struct endosim_state *out)
{
	memset(out, 0, sizeof(*out));
	fields_from_record(&fields_status, in, out);
	out->publish_ns = in->stamp_ns;
	out->fault_axis = -1;
	if (!out->patient.enabled) {
		no_patient(&out->patient);
	}
	if (out->tool.kind == ENDOSIM_TOOL_NONE) {
		no_tool(&out->tool);
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		out->axis[a].feedback_ns = in->stamp_ns;
	}
}

/* --- the rod's shape ---------------------------------------------------- */

#define SHAPE_HEAD offsetof(struct session_shape, point)

_Static_assert(SHAPE_HEAD == 40, "session_shape: its head is the format");

uint32_t session_shape_every(uint64_t period_ns)
{
	uint64_t every = period_ns ? ENDOSIM_NS_PER_S /
					     (SESSION_SHAPE_HZ * period_ns)
				   : 1;

	return every > 1 ? (uint32_t)every : 1;
}

bool session_shape_due(const struct endosim_state *st, uint32_t every)
{
	return st->rod.model == ENDOSIM_MODEL_ROD && st->cycle % every == 0;
}

static uint32_t at_most(uint32_t n, uint32_t max)
{
	return n < max ? n : max;
}

void session_shape_from_state(const struct endosim_state *in,
			      struct session_shape *out)
{
	const struct endosim_rod_state *r = &in->rod;

	out->cycle = in->cycle;
	out->stamp_ns = in->stamp_ns;
	out->points = at_most(r->points, ENDOSIM_ROD_POINTS);
	out->nodes = at_most(r->nodes, ENDOSIM_COLON_NODES);
	memcpy(out->span_nodes, r->span_nodes, sizeof(out->span_nodes));
	memcpy(out->point, r->point, out->points * sizeof(out->point[0]));
	memcpy(out->roll, r->roll, out->points * sizeof(out->roll[0]));
	memcpy(out->node, r->node, out->nodes * sizeof(out->node[0]));
}

/* The largest of nodes [FIRST, FIRST + N) of S's displacements, m. */
static double largest(const struct session_shape *s, uint32_t first,
		      uint32_t n)
{
	double most = 0;

	for (uint32_t i = first; i < first + n && i < s->nodes; i++) {
		const float *y = s->node[i];
		double d = sqrt((double)y[0] * y[0] + (double)y[1] * y[1] +
				(double)y[2] * y[2]);

		most = d > most ? d : most;
	}
	return most;
}

void session_shape_to_state(const struct session_shape *in,
			    struct endosim_state *out)
{
	struct endosim_rod_state *r = &out->rod;
	uint32_t first = 0;

	r->points = at_most(in->points, ENDOSIM_ROD_POINTS);
	r->nodes = at_most(in->nodes, ENDOSIM_COLON_NODES);
	memset(r->point, 0, sizeof(r->point));
	memset(r->roll, 0, sizeof(r->roll));
	memset(r->node, 0, sizeof(r->node));
	memcpy(r->point, in->point, r->points * sizeof(r->point[0]));
	memcpy(r->roll, in->roll, r->points * sizeof(r->roll[0]));
	memcpy(r->node, in->node, r->nodes * sizeof(r->node[0]));
	memcpy(r->span_nodes, in->span_nodes, sizeof(r->span_nodes));
	for (int k = 0; k < ENDOSIM_SPANS; k++) {
		out->scope.bow_m[k] = largest(in, first, in->span_nodes[k]);
		first += in->span_nodes[k];
	}
}

/* The payload's length for S's counts. */
static size_t shape_length(const struct session_shape *s)
{
	return SHAPE_HEAD + s->points * (sizeof(s->point[0]) +
					 sizeof(s->roll[0])) +
	       s->nodes * sizeof(s->node[0]);
}

uint32_t session_shape_pack(const struct session_shape *s, void *out)
{
	unsigned char *p = out;

	memcpy(p, s, SHAPE_HEAD);
	p += SHAPE_HEAD;
	memcpy(p, s->point, s->points * sizeof(s->point[0]));
	p += s->points * sizeof(s->point[0]);
	memcpy(p, s->roll, s->points * sizeof(s->roll[0]));
	p += s->points * sizeof(s->roll[0]);
	memcpy(p, s->node, s->nodes * sizeof(s->node[0]));
	return (uint32_t)shape_length(s);
}

/*
 * The head of a SHAPE frame's PAYLOAD (LENGTH bytes) into OUT, when its
 * counts fit the arrays, the spans' nodes the nodes, and the arrays the
 * payload.
 */
static bool shape_head(const unsigned char *payload, size_t length,
		       struct session_shape *out)
{
	uint32_t spans = 0;

	if (length < SHAPE_HEAD) {
		return false;
	}
	memcpy(out, payload, SHAPE_HEAD);
	for (int k = 0; k < ENDOSIM_SPANS; k++) {
		spans += at_most(out->span_nodes[k], ENDOSIM_COLON_NODES);
	}
	return out->points <= ENDOSIM_ROD_POINTS &&
	       out->nodes <= ENDOSIM_COLON_NODES && spans <= out->nodes &&
	       shape_length(out) <= length;
}

/* A good SHAPE payload (shape_head()) into OUT. */
static void shape_unpack(const unsigned char *p, size_t length,
			 struct session_shape *out)
{
	shape_head(p, length, out);
	p += SHAPE_HEAD;
	memcpy(out->point, p, out->points * sizeof(out->point[0]));
	p += out->points * sizeof(out->point[0]);
	memcpy(out->roll, p, out->points * sizeof(out->roll[0]));
	p += out->points * sizeof(out->roll[0]);
	memcpy(out->node, p, out->nodes * sizeof(out->node[0]));
}

/* --- framing ------------------------------------------------------------ */

static void put_u32(unsigned char *p, uint32_t v)
{
	p[0] = (unsigned char)v;
	p[1] = (unsigned char)(v >> 8);
	p[2] = (unsigned char)(v >> 16);
	p[3] = (unsigned char)(v >> 24);
}

static uint32_t get_u32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

uint32_t session_crc32(uint32_t crc, const void *data, size_t n)
{
	return (uint32_t)crc32_z(crc, data, n);
}

size_t session_frame_put(unsigned char *buf, size_t size, size_t used,
			 uint32_t type, const void *payload, uint32_t length)
{
	size_t need = FRAME_OVERHEAD + length;
	unsigned char *p = buf + used;

	if (used > size || size - used < need) {
		return 0;
	}
	put_u32(p, type);
	put_u32(p + 4, length);
	if (length) {
		memcpy(p + 8, payload, length);
	}
	put_u32(p + 8 + length, session_crc32(0, p, 8 + (size_t)length));
	return need;
}

static int write_all(int fd, const void *data, size_t n)
{
	const unsigned char *p = data;

	while (n) {
		ssize_t w = write(fd, p, n);

		if (w < 0) {
			if (errno == EINTR) {
				continue;
			}
			return -errno;
		}
		if (w == 0) {
			return -EIO;
		}
		p += w;
		n -= (size_t)w;
	}
	return 0;
}

int session_header_text(const struct session_header *h, char *buf,
			size_t size)
{
	int n = snprintf(buf, size,
			 "format=%u\nid=%" PRIu64 "\ntrainee=%s\ncase=%s\n"
			 "started=%s\nstart_ns=%" PRIu64 "\nperiod_ns=%" PRIu64
			 "\nversion=%s\nrecord_size=%zu\nstep_m=%.17g\n"
			 "ring_vertices=%d\nsegment_m=%.17g\n",
			 SESSION_FILE_FORMAT, h->id, h->trainee, h->case_name,
			 h->started, h->start_ns, h->period_ns, h->version,
			 sizeof(struct session_record), h->step_m,
			 h->ring_vertices, h->segment_m);

	return n < 0 || (size_t)n >= size ? -ENAMETOOLONG : n;
}

int session_file_write_magic(int fd)
{
	return write_all(fd, SESSION_FILE_MAGIC, 8);
}

int session_file_write_frame(int fd, uint32_t type, const void *payload,
			     uint32_t length)
{
	unsigned char head[8], tail[4];
	uint32_t crc;
	int r;

	put_u32(head, type);
	put_u32(head + 4, length);
	crc = session_crc32(0, head, 8);
	crc = session_crc32(crc, payload, length);
	put_u32(tail, crc);
	r = write_all(fd, head, 8);
	if (r == 0 && length) {
		r = write_all(fd, payload, length);
	}
	return r ? r : write_all(fd, tail, 4);
}

/* --- reading ---------------------------------------------------------- */

/* The file's bytes: mapped (a regular file), else read into a buffer. */
struct input {
	unsigned char *data;
	size_t len;
	bool mapped;
};

/* Reads the whole of FD into a new buffer (a pipe, a device). */
static int slurp(int fd, const struct stat *st, unsigned char **out,
		 size_t *len)
{
	size_t cap, n = 0;
	unsigned char *buf;

	cap = st->st_size > 0 ? (size_t)st->st_size + 1 : 4096;
	buf = malloc(cap);
	if (!buf) {
		return -ENOMEM;
	}
	for (;;) {
		ssize_t r;

		if (n == cap) {
			unsigned char *b = realloc(buf, cap * 2);

			if (!b) {
				free(buf);
				return -ENOMEM;
			}
			buf = b;
			cap *= 2;
		}
		r = read(fd, buf + n, cap - n);
		if (r < 0) {
			if (errno == EINTR) {
				continue;
			}
			r = -errno;
			free(buf);
			return (int)r;
		}
		if (r == 0) {
			break;
		}
		n += (size_t)r;
	}
	*out = buf;
	*len = n;
	return 0;
}

/*
 * The whole of FD in IN. A regular file is mapped rather than read, so
 * that a long session is not held twice on the heap (its bytes, then its
 * records). The writer only appends: a file that grows meanwhile is read
 * as it was at fstat().
 */
static int load(int fd, struct input *in)
{
	struct stat st;
	void *p;

	memset(in, 0, sizeof(*in));
	if (fstat(fd, &st) < 0) {
		return -errno;
	}
	if (!S_ISREG(st.st_mode)) {
		return slurp(fd, &st, &in->data, &in->len);
	}
	if (st.st_size == 0) {
		return 0;
	}
	p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE, fd, 0);
	if (p == MAP_FAILED) {
		return -errno;
	}
	in->data = p;
	in->len = (size_t)st.st_size;
	in->mapped = true;
	return 0;
}

static void unload(struct input *in)
{
	if (in->mapped) {
		munmap(in->data, in->len);
	} else {
		free(in->data);
	}
}

/* The next good frame at OFF of DATA (LEN bytes), or false. */
static bool next_frame(const unsigned char *data, size_t len, size_t off,
		       uint32_t *type, const unsigned char **payload,
		       uint32_t *length)
{
	uint32_t n;

	if (len - off < FRAME_OVERHEAD) {
		return false;
	}
	n = get_u32(data + off + 4);
	if (n > SESSION_FRAME_MAX || len - off - FRAME_OVERHEAD < n) {
		return false;
	}
	if (session_crc32(0, data + off, 8 + (size_t)n) !=
	    get_u32(data + off + 8 + n)) {
		return false;
	}
	*type = get_u32(data + off);
	*payload = data + off + 8;
	*length = n;
	return true;
}

static char *text_copy(char **dst, char *room, const unsigned char *src,
		       uint32_t n)
{
	memcpy(room, src, n);
	room[n] = '\0';
	*dst = room;
	return room + n + 1;
}

/* A record of LENGTH bytes, of this format or another, as this one's. */
static void record_copy(struct session_record *rec, const void *payload,
			size_t length)
{
	size_t n = length < sizeof(*rec) ? length : sizeof(*rec);

	memset(rec, 0, sizeof(*rec));
	memcpy(rec, payload, n);
	if (n < SESSION_RECORD_SIZE_5) { /* format 4 or older: nothing torn,
					     no pain */
		rec->pain_place = -1;
		rec->torn_segment = -1;
	}
	if (n < SESSION_RECORD_SIZE_6) { /* format 5 or older: no tool */
		rec->tool_captured = -1;
		rec->tool_event_polyp = -1;
	}
	if (n <= SESSION_RECORD_SIZE_7) { /* format 7 or older: none lying */
		rec->tool_lying_polyp = -1;
	}
}

/* The record size HEADER says in *SAID; false when it says none. */
static bool said_record_size(const char *header, size_t *said)
{
	char size[32];

	if (session_text_get(header, "record_size", size, sizeof(size))) {
		return false;
	}
	*said = strtoul(size, NULL, 10);
	return true;
}

/*
 * Whether a file whose records are LENGTH bytes long (0: none) and whose
 * HEADER says their size can be read: format 1's records or longer.
 */
static bool record_size_ok(const char *header, size_t length)
{
	size_t said;

	if (!said_record_size(header, &said)) {
		return length == 0 || length >= SESSION_RECORD_SIZE_1;
	}
	return said >= SESSION_RECORD_SIZE_1 && (!length || length == said);
}

/* What a file holds: a first pass over its good frames. */
struct tally {
	size_t records, events, shapes;
	size_t record_length;     /* the records' (0: none) */
	size_t text;              /* the texts' bytes and their NULs */
	size_t shape_bytes;       /* the SHAPE frames' payloads */
	size_t good;              /* where the good frames end */
};

static bool is_text(uint32_t type)
{
	return type == SESSION_FRAME_HEADER || type == SESSION_FRAME_CONFIG ||
	       type == SESSION_FRAME_CASE || type == SESSION_FRAME_END;
}

/* Counts the frames of DATA (LEN bytes) after the magic. 0, or -EPROTO
 * for records of two sizes. */
static int tally(const unsigned char *data, size_t len, struct tally *t)
{
	const unsigned char *payload;
	struct session_shape head;
	uint32_t type, length;
	size_t off;

	memset(t, 0, sizeof(*t));
	for (off = 8; next_frame(data, len, off, &type, &payload, &length);
	     off += FRAME_OVERHEAD + length) {
		if (type == SESSION_FRAME_RECORD) {
			if (t->records && length != t->record_length) {
				return -EPROTO;
			}
			t->record_length = length;
			t->records++;
		} else if (type == SESSION_FRAME_EVENT) {
			if (length < sizeof(struct session_event)) {
				break; /* damaged: stop as at a cut */
			}
			t->events++;
			t->text += length - sizeof(struct session_event) + 1;
		} else if (type == SESSION_FRAME_SHAPE) {
			if (!shape_head(payload, length, &head)) {
				break; /* damaged: stop as at a cut */
			}
			t->shapes++;
			t->shape_bytes += length;
		} else if (is_text(type)) {
			t->text += (size_t)length + 1;
		}
	}
	t->good = off;
	return 0;
}

/* Where a text frame of TYPE goes in OUT; NULL: nowhere (not a text, or
 * a header after the first). */
static char **text_of(struct session_file *out, uint32_t type)
{
	switch (type) {
	case SESSION_FRAME_HEADER:
		return out->header ? NULL : &out->header;
	case SESSION_FRAME_CONFIG:
		return &out->config;
	case SESSION_FRAME_CASE:
		return &out->case_text;
	case SESSION_FRAME_END:
		return &out->end;
	default:
		return NULL;
	}
}

/* Where the next text and SHAPE payload go in the storage. */
struct rooms {
	char *text;
	unsigned char *shape;
};

/* One good frame into OUT. */
static void take(struct session_file *out, uint32_t type,
		 const unsigned char *payload, uint32_t length,
		 struct rooms *room)
{
	struct session_file_event *e;
	struct session_file_shape *sh;
	char **text = text_of(out, type);

	switch (type) {
	case SESSION_FRAME_RECORD:
		record_copy(&out->records[out->n_records++], payload, length);
		break;
	case SESSION_FRAME_EVENT:
		e = &out->events[out->n_events++];
		memcpy(&e->ev, payload, sizeof(e->ev));
		room->text = text_copy(&e->text, room->text,
				       payload + sizeof(e->ev),
				       length - (uint32_t)sizeof(e->ev));
		break;
	case SESSION_FRAME_SHAPE:
		sh = &out->shapes[out->n_shapes++];
		memcpy(&sh->stamp_ns, payload +
		       offsetof(struct session_shape, stamp_ns),
		       sizeof(sh->stamp_ns));
		memcpy(room->shape, payload, length);
		sh->payload = room->shape;
		sh->length = length;
		room->shape += length;
		break;
	default:
		if (text) {
			room->text = text_copy(text, room->text, payload,
					       length);
		}
		break; /* or a type of a later format: skipped */
	}
}

/*
 * OUT's arrays in one allocation for what T counted; -ENOMEM. The
 * records (packed, 4-byte aligned) take their room rounded up to the
 * events' alignment, so that the events and the shapes after them are
 * aligned (their sizes are multiples of it).
 */
static int place(struct session_file *out, const struct tally *t,
		 struct rooms *room)
{
	const size_t align = _Alignof(struct session_file_event);
	size_t records = (t->records * sizeof(struct session_record) +
			  align - 1) / align * align;
	unsigned char *store = malloc(
		records + t->events * sizeof(struct session_file_event) +
		t->shapes * sizeof(struct session_file_shape) +
		t->shape_bytes + t->text + 1);

	_Static_assert(sizeof(struct session_file_event) %
				       _Alignof(struct session_file_shape) ==
			       0,
		       "session_file: the shapes follow the events aligned");
	if (!store) {
		return -ENOMEM;
	}
	out->storage = store;
	out->records = (struct session_record *)store;
	out->events = (struct session_file_event *)(store + records);
	out->shapes = (struct session_file_shape *)(out->events + t->events);
	room->shape = (unsigned char *)(out->shapes + t->shapes);
	room->text = (char *)room->shape + t->shape_bytes;
	return 0;
}

int session_file_read(const char *path, struct session_file *out)
{
	struct input in;
	const unsigned char *payload;
	uint32_t type, length;
	struct tally t;
	struct rooms room;
	int fd, r;

	memset(out, 0, sizeof(*out));
	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0) {
		return -errno;
	}
	r = load(fd, &in);
	close(fd);
	if (r) {
		return r;
	}
	if (in.len < 8 || memcmp(in.data, SESSION_FILE_MAGIC, 8) != 0 ||
	    !next_frame(in.data, in.len, 8, &type, &payload, &length) ||
	    type != SESSION_FRAME_HEADER) {
		unload(&in);
		return -EBADMSG;
	}
	r = tally(in.data, in.len, &t);
	r = r ? r : place(out, &t, &room);
	for (size_t off = 8; !r && off < t.good;
	     off += FRAME_OVERHEAD + length) {
		next_frame(in.data, in.len, off, &type, &payload, &length);
		take(out, type, payload, length, &room);
	}
	out->bytes_read = t.good;
	out->bytes_ignored = in.len - t.good;
	unload(&in);
	if (!r && !record_size_ok(out->header, t.record_length)) {
		r = -EPROTO;
	}
	out->record_size = t.record_length;
	if (!r && !t.record_length) {
		said_record_size(out->header, &out->record_size);
	}
	if (r) {
		session_file_close(out);
	}
	return r;
}

void session_file_close(struct session_file *f)
{
	free(f->storage);
	memset(f, 0, sizeof(*f));
}

int session_text_get(const char *text, const char *key, char *out,
		     size_t size)
{
	size_t k = strlen(key);

	for (const char *p = text; p && *p;) {
		const char *nl = strchr(p, '\n');
		size_t n = nl ? (size_t)(nl - p) : strlen(p);

		if (n > k && strncmp(p, key, k) == 0 && p[k] == '=') {
			size_t v = n - k - 1;

			if (size == 0) {
				return -ENOSPC;
			}
			if (v >= size) {
				v = size - 1;
			}
			memcpy(out, p + k + 1, v);
			out[v] = '\0';
			return 0;
		}
		p = nl ? nl + 1 : p + n;
	}
	return -ENOENT;
}

/*
 * The last of N items from BASE, SIZE bytes apart, whose time stamp (a
 * uint64_t STAMP bytes into each) is at or before STAMP_NS: 0 if none is.
 */
static size_t last_at(const void *base, size_t n, size_t size, size_t stamp,
		      uint64_t stamp_ns)
{
	const unsigned char *p = base;
	size_t lo = 0, hi = n;

	/* the first item after STAMP_NS, then one back */
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		uint64_t t;

		memcpy(&t, p + mid * size + stamp, sizeof(t));
		if (t <= stamp_ns) {
			lo = mid + 1;
		} else {
			hi = mid;
		}
	}
	return lo ? lo - 1 : 0;
}

size_t session_file_seek(const struct session_file *f, uint64_t stamp_ns)
{
	return last_at(f->records, f->n_records, sizeof(f->records[0]),
		       offsetof(struct session_record, stamp_ns), stamp_ns);
}

size_t session_file_seek_shape(const struct session_file *f,
			       uint64_t stamp_ns)
{
	return last_at(f->shapes, f->n_shapes, sizeof(f->shapes[0]),
		       offsetof(struct session_file_shape, stamp_ns),
		       stamp_ns);
}

void session_file_shape(const struct session_file *f, size_t i,
			struct session_shape *out)
{
	shape_unpack(f->shapes[i].payload, f->shapes[i].length, out);
}
