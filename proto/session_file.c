/* session_file.c - the training session file (session_file.h). */
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "session_file.h"

#include "fields.h"

#define FRAME_OVERHEAD 12u /* type, length, crc */

void session_record_from_state(const struct endosim_state *in,
			       struct session_record *out)
{
	memset(out, 0, sizeof(*out));
	fields_to_record(&fields_status, in, out);
}

void session_record_to_state(const struct session_record *in,
			     struct endosim_state *out)
{
	memset(out, 0, sizeof(*out));
	fields_from_record(&fields_status, in, out);
	out->publish_ns = in->stamp_ns;
	out->fault_axis = -1;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		out->axis[a].feedback_ns = in->stamp_ns;
	}
}

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
}

/*
 * Whether a file whose records are LENGTH bytes long (0: none) and whose
 * HEADER says their size can be read: format 1's records or longer.
 */
static bool record_size_ok(const char *header, size_t length)
{
	char size[32];
	unsigned long said;

	if (session_text_get(header, "record_size", size, sizeof(size))) {
		return length == 0 || length >= SESSION_RECORD_SIZE_1;
	}
	said = strtoul(size, NULL, 10);
	return said >= SESSION_RECORD_SIZE_1 && (!length || length == said);
}

int session_file_read(const char *path, struct session_file *out)
{
	struct input in;
	const unsigned char *data;
	size_t len, off, n_rec = 0, n_ev = 0, text = 0, good, rec_len = 0;
	const unsigned char *payload;
	uint32_t type, length;
	char *room;
	unsigned char *store;
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
	data = in.data;
	len = in.len;
	if (len < 8 || memcmp(data, SESSION_FILE_MAGIC, 8) != 0 ||
	    !next_frame(data, len, 8, &type, &payload, &length) ||
	    type != SESSION_FRAME_HEADER) {
		unload(&in);
		return -EBADMSG;
	}
	/* first pass: count, and find where the good frames end */
	for (off = 8; next_frame(data, len, off, &type, &payload, &length);
	     off += FRAME_OVERHEAD + length) {
		if (type == SESSION_FRAME_RECORD) {
			if (n_rec && length != rec_len) {
				unload(&in);
				return -EPROTO;
			}
			rec_len = length;
			n_rec++;
		} else if (type == SESSION_FRAME_EVENT) {
			if (length < sizeof(struct session_event)) {
				break; /* damaged: stop as at a cut */
			}
			n_ev++;
			text += length - sizeof(struct session_event) + 1;
		} else if (type == SESSION_FRAME_HEADER ||
			   type == SESSION_FRAME_CONFIG ||
			   type == SESSION_FRAME_CASE ||
			   type == SESSION_FRAME_END) {
			text += (size_t)length + 1;
		}
	}
	good = off;
	store = malloc(n_rec * sizeof(struct session_record) +
		       n_ev * sizeof(struct session_file_event) + text + 1);
	if (!store) {
		unload(&in);
		return -ENOMEM;
	}
	out->storage = store;
	out->records = (struct session_record *)store;
	out->events = (struct session_file_event *)
		(store + n_rec * sizeof(struct session_record));
	room = (char *)(out->events + n_ev);
	for (off = 8; off < good; off += FRAME_OVERHEAD + length) {
		next_frame(data, len, off, &type, &payload, &length);
		switch (type) {
		case SESSION_FRAME_RECORD:
			record_copy(&out->records[out->n_records++], payload,
				    length);
			break;
		case SESSION_FRAME_EVENT: {
			struct session_file_event *e =
				&out->events[out->n_events++];

			memcpy(&e->ev, payload, sizeof(e->ev));
			room = text_copy(&e->text, room,
					 payload + sizeof(e->ev),
					 length - (uint32_t)sizeof(e->ev));
			break;
		}
		case SESSION_FRAME_HEADER:
			if (!out->header) {
				room = text_copy(&out->header, room, payload,
						 length);
			}
			break;
		case SESSION_FRAME_CONFIG:
			room = text_copy(&out->config, room, payload, length);
			break;
		case SESSION_FRAME_CASE:
			room = text_copy(&out->case_text, room, payload,
					 length);
			break;
		case SESSION_FRAME_END:
			room = text_copy(&out->end, room, payload, length);
			break;
		default:
			break; /* a type of a later format: skipped */
		}
	}
	out->bytes_read = good;
	out->bytes_ignored = len - good;
	unload(&in);
	if (!record_size_ok(out->header, n_rec ? rec_len : 0)) {
		session_file_close(out);
		return -EPROTO;
	}
	return 0;
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

size_t session_file_seek(const struct session_file *f, uint64_t stamp_ns)
{
	size_t lo = 0, hi = f->n_records;

	/* the first record after STAMP_NS, then one back */
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;

		if (f->records[mid].stamp_ns <= stamp_ns) {
			lo = mid + 1;
		} else {
			hi = mid;
		}
	}
	return lo ? lo - 1 : 0;
}
