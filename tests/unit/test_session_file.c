/* test_session_file.c - the session file: frames written and read back,
 * a file cut at every byte reads up to its last complete frame, damage
 * stops the reader, the record's round trip through a published state. */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "proto/session_file.h"
#include "session/sessionview.h"

#define RECORDS 20

static char path[64];
static char header[128];
#define HEADER_FRAME (12 + strlen(header))

static int setup(void **state)
{
	(void)state;
	snprintf(path, sizeof(path), "/tmp/test_session_file.%d", getpid());
	snprintf(header, sizeof(header), "format=2\nid=7\ntrainee=A. Trainee\n"
		 "record_size=%zu\n", sizeof(struct session_record));
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	unlink(path);
	return 0;
}

/* A session of RECORDS records and one event after the 10th; its size. */
static size_t write_session(bool end)
{
	int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
	struct session_event ev = { .stamp_ns = 10500, .kind = 2,
				    .axis = 1, .value = 0.5 };
	unsigned char ebuf[sizeof(ev) + 5];
	off_t size;

	assert_true(fd >= 0);
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  header, strlen(header)), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_CASE,
						  "segment rectum 0.15\n", 20),
			 0);
	for (int i = 0; i < RECORDS; i++) {
		struct session_record r = { .cycle = (uint64_t)i,
					    .stamp_ns = 1000u * (uint64_t)i,
					    .depth_m = 0.01f * (float)i };

		assert_int_equal(session_file_write_frame(
					 fd, SESSION_FRAME_RECORD, &r,
					 sizeof(r)), 0);
		if (i == 10) {
			memcpy(ebuf, &ev, sizeof(ev));
			memcpy(ebuf + sizeof(ev), "drive", 5);
			assert_int_equal(session_file_write_frame(
						 fd, SESSION_FRAME_EVENT, ebuf,
						 sizeof(ebuf)), 0);
		}
	}
	if (end) {
		assert_int_equal(session_file_write_frame(
					 fd, SESSION_FRAME_END, "cecum_s=3\n",
					 10), 0);
	}
	size = lseek(fd, 0, SEEK_CUR);
	close(fd);
	return (size_t)size;
}

static void test_round_trip(void **state)
{
	struct session_file f;
	char v[64];

	(void)state;
	write_session(true);
	assert_int_equal(session_file_read(path, &f), 0);
	assert_int_equal(f.n_records, RECORDS);
	assert_int_equal(f.n_events, 1);
	assert_int_equal(f.bytes_ignored, 0);
	for (int i = 0; i < RECORDS; i++) {
		assert_int_equal(f.records[i].cycle, i);
		assert_true(f.records[i].depth_m == 0.01f * (float)i);
	}
	assert_int_equal(f.events[0].ev.kind, 2);
	assert_int_equal(f.events[0].ev.axis, 1);
	assert_string_equal(f.events[0].text, "drive");
	assert_string_equal(f.case_text, "segment rectum 0.15\n");
	assert_null(f.config);
	assert_string_equal(f.end, "cecum_s=3\n");
	assert_int_equal(session_text_get(f.header, "trainee", v, sizeof(v)),
			 0);
	assert_string_equal(v, "A. Trainee");
	assert_int_equal(session_text_get(f.header, "train", v, sizeof(v)),
			 -ENOENT);
	assert_int_equal(session_text_get(f.end, "cecum_s", v, sizeof(v)), 0);
	assert_string_equal(v, "3");
	/* seek: the last record at or before a time */
	assert_int_equal(session_file_seek(&f, 0), 0);
	assert_int_equal(session_file_seek(&f, 2999), 2);
	assert_int_equal(session_file_seek(&f, 3000), 3);
	assert_int_equal(session_file_seek(&f, 1u << 30), RECORDS - 1);
	session_file_close(&f);
	session_file_close(&f); /* safe twice */
}

/*
 * Cut the file at every length: each reads (or is refused as no session
 * file before its header is whole) with exactly the records that were
 * complete, never more, never a crash.
 */
static void test_cut_everywhere(void **state)
{
	size_t full = write_session(false);
	size_t rec_frame = 12 + sizeof(struct session_record);
	size_t head = 8 + HEADER_FRAME + 12 + 20; /* magic, header, case */
	unsigned char *whole = malloc(full);
	struct session_file f;
	int fd = open(path, O_RDONLY);

	(void)state;
	assert_non_null(whole);
	assert_int_equal(read(fd, whole, full), (ssize_t)full);
	close(fd);
	for (size_t n = 0; n <= full; n++) {
		size_t expect;
		int r;

		/* the file as a crash after its first N bytes leaves it */
		fd = open(path, O_WRONLY | O_TRUNC);
		assert_int_equal(write(fd, whole, n), (ssize_t)n);
		close(fd);
		r = session_file_read(path, &f);
		if (n < 8 + HEADER_FRAME) {
			assert_int_equal(r, -EBADMSG);
			continue;
		}
		assert_int_equal(r, 0);
		expect = n < head ? 0 : (n - head) / rec_frame;
		/* the event after record 10 takes 12 + 37 bytes */
		if (expect > 11) {
			expect = n < head + 11 * rec_frame + 49
					 ? 11
					 : (n - head - 49) / rec_frame;
		}
		assert_int_equal(f.n_records, expect);
		assert_int_equal(f.bytes_read + f.bytes_ignored, n);
		assert_null(f.end);
		session_file_close(&f);
	}
	free(whole);
}

/* A flipped byte in a record: the reader stops before it. */
static void test_damage_stops(void **state)
{
	size_t head = 8 + HEADER_FRAME + 12 + 20;
	size_t rec_frame = 12 + sizeof(struct session_record);
	struct session_file f;
	unsigned char b;
	int fd;

	(void)state;
	write_session(true);
	fd = open(path, O_RDWR);
	assert_true(fd >= 0);
	assert_int_equal(pread(fd, &b, 1, (off_t)(head + 5 * rec_frame + 30)),
			 1);
	b ^= 0x10;
	assert_int_equal(pwrite(fd, &b, 1,
				(off_t)(head + 5 * rec_frame + 30)), 1);
	close(fd);
	assert_int_equal(session_file_read(path, &f), 0);
	assert_int_equal(f.n_records, 5);
	assert_true(f.bytes_ignored > 0);
	session_file_close(&f);
	/* not a session file at all */
	fd = open(path, O_WRONLY | O_TRUNC);
	assert_int_equal(write(fd, "[rig]\nbackend=sim\n", 18), 18);
	close(fd);
	assert_int_equal(session_file_read(path, &f), -EBADMSG);
	assert_int_equal(session_file_read("/nonexistent/x", &f), -ENOENT);
}

/* A file whose HEADER says HEAD and whose records are LENGTH bytes: the
 * first FIELDS of a record like r(i), then zeros. Its records read back,
 * or its error. */
static int read_sized(const char *head, size_t length, size_t fields,
		      struct session_file *f)
{
	int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
	unsigned char raw[640] = { 0 };

	assert_true(fd >= 0 && length <= sizeof(raw));
	assert_true(fields <= length && fields <= sizeof(struct session_record));
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  head, strlen(head)), 0);
	for (int i = 0; i < 3; i++) {
		struct session_record r = {
			.cycle = (uint64_t)i, .compute_ns = 7u + (uint32_t)i,
			.trans_rod_n = 2.5f, .friction_n = 0.5f,
			.guide_phase = 3, .guide_force = { 0, 0, 0, 1.5f },
			.patient = 1, .gas_m3 = 0.002f, .hand_site = 1,
			.burst_segment = -1, .lumen_factor = { [8] = 1.2f },
			.pain = 4.5f, .torn_segment = 2,
			.tool_kind = ENDOSIM_TOOL_SNARE, .tool_captured = 3,
			.tool_event_polyp = 3, .tool_bleed_m3_s = 2e-8f,
			.tool_lying_polyp = 4,
			.tool_lying_at = { 0.1f, 0.2f, 0.3f },
		};

		memcpy(raw, &r, fields);
		assert_int_equal(session_file_write_frame(
					 fd, SESSION_FRAME_RECORD, raw,
					 (uint32_t)length), 0);
	}
	close(fd);
	return session_file_read(path, f);
}

/* The header row of F's CSV (sessionview.h) in OUT. */
static void csv_header(const struct session_file *f, char *out, size_t size)
{
	FILE *m = fmemopen(out, size, "w");

	assert_non_null(m);
	assert_int_equal(sessionview_csv(m, f), 0);
	fclose(m);
	out[strcspn(out, "\n")] = '\0';
}

/*
 * A file in format 1's layout (304-byte records, its last two words the
 * zero reserved ones), 2's (320 bytes) or 3's (360) reads with the fields
 * added since zero (and a replay's state has no patient then); a later
 * format's longer records by the fields this one knows; records shorter
 * than format 1's, or not the size the header says, are refused. The CSV
 * of a file of format 3 or older has format 3's columns, a format-4
 * file's the patient's body's too (and nothing torn by the tip), a
 * format-5 file's its pain as well (and no tool), a
 * format-6 file's the tool's too (and no bleeding), a format-7 file's
 * the bleeding's flow as well (and none lying), a format-8 file's the
 * cut polyp lying as well.
 */
static void test_old_layout(void **state)
{
	const size_t v1 = offsetof(struct session_record, trans_rod_n);
	const size_t v2 = offsetof(struct session_record, guide_phase);
	const size_t v3 = offsetof(struct session_record, patient);
	const size_t all = sizeof(struct session_record);
	static char csv[8192];
	struct endosim_state st;
	struct session_file f;

	(void)state;
	/* format 1's reserved words are where the rod's forces went */
	assert_int_equal(SESSION_RECORD_SIZE_1,
			 offsetof(struct session_record, model));
	assert_int_equal(read_sized("format=1\nrecord_size=304\n", 304, v1,
				    &f), 0);
	assert_int_equal(f.n_records, 3);
	for (size_t i = 0; i < f.n_records; i++) {
		assert_int_equal(f.records[i].cycle, i);
		assert_int_equal(f.records[i].compute_ns, 7 + i);
		assert_true(f.records[i].trans_rod_n == 0);
		assert_true(f.records[i].friction_n == 0);
	}
	session_file_close(&f);
	/* format 2's (the rod's, no guidance): the guidance's fields zero */
	assert_int_equal(read_sized("format=2\nrecord_size=320\n", 320, v2,
				    &f), 0);
	assert_true(f.records[1].friction_n == 0.5f);
	assert_int_equal(f.records[1].guide_phase, 0);
	assert_true(f.records[1].guide_force[3] == 0);
	session_file_close(&f);
	/* format 3's (guided replay, no patient): the patient's fields zero,
	   the replay's state the disabled patient's; format 3's columns */
	assert_int_equal(SESSION_RECORD_SIZE_3, v3);
	assert_int_equal(read_sized("format=3\nrecord_size=360\n", 360, v3,
				    &f), 0);
	assert_int_equal(f.record_size, 360);
	assert_int_equal(f.records[1].guide_phase, 3);
	assert_int_equal(f.records[1].patient, 0);
	assert_int_equal(f.records[1].hand_site, 0);
	assert_true(f.records[1].gas_m3 == 0);
	session_record_to_state(&f.records[1], &st);
	assert_int_equal(st.patient.hand_site, -1);
	assert_int_equal(st.patient.burst_segment, -1);
	assert_true(st.patient.factor[8] == 1);
	csv_header(&f, csv, sizeof(csv));
	assert_non_null(strstr(csv, ",guide_force_wheel_lr_nm"));
	assert_null(strstr(csv, "patient"));
	session_file_close(&f);
	/* format 4's: the patient's columns; nothing torn by the tip, no
	   pain's place */
	assert_int_equal(SESSION_RECORD_SIZE_4,
			 offsetof(struct session_record, sedation));
	assert_int_equal(read_sized("format=4\nrecord_size=488\n", 488,
				    SESSION_RECORD_SIZE_4, &f), 0);
	assert_int_equal(f.records[1].torn_segment, -1);
	assert_int_equal(f.records[1].pain_place, -1);
	session_record_to_state(&f.records[1], &st);
	assert_int_equal(st.patient.enabled, 1);
	assert_int_equal(st.patient.hand_site, 1);
	assert_true(st.patient.factor[8] == (double)1.2f);
	assert_true(st.patient.factor[0] == 0); /* as recorded */
	csv_header(&f, csv, sizeof(csv));
	assert_non_null(strstr(csv, ",guide_force_wheel_lr_nm,patient_enabled,"));
	assert_non_null(strstr(csv, ",patient_burst_segment"));
	assert_null(strstr(csv, "patient_pain"));
	session_file_close(&f);
	assert_int_equal(read_sized("format=5\nrecord_size=520\n", 520,
				    SESSION_RECORD_SIZE_5, &f), 0);
	assert_int_equal(SESSION_RECORD_SIZE_5,
			 offsetof(struct session_record, tool_kind));
	assert_int_equal(f.records[2].compute_ns, 9);
	assert_true(f.records[2].trans_rod_n == 2.5f);
	assert_true(f.records[2].friction_n == 0.5f);
	assert_int_equal(f.records[2].guide_phase, 3);
	assert_true(f.records[2].guide_force[3] == 1.5f);
	assert_int_equal(f.records[2].hand_site, 1);
	assert_int_equal(f.records[2].burst_segment, -1);
	assert_true(f.records[2].gas_m3 == 0.002f);
	assert_int_equal(f.records[2].torn_segment, 2);
	assert_true(f.records[2].pain == 4.5f);
	csv_header(&f, csv, sizeof(csv));
	assert_non_null(strstr(csv, ",patient_pain,"));
	assert_non_null(strstr(csv, ",patient_torn_segment"));
	assert_null(strstr(csv, "tool"));
	/* format 5's: no tool, nothing held */
	assert_int_equal(f.records[2].tool_kind, ENDOSIM_TOOL_NONE);
	assert_int_equal(f.records[2].tool_captured, -1);
	assert_int_equal(f.records[2].tool_event_polyp, -1);
	session_record_to_state(&f.records[2], &st);
	assert_int_equal(st.tool.captured, -1);
	f.records[2].tool_captured = 0; /* a writer's zero: still none */
	session_record_to_state(&f.records[2], &st);
	assert_int_equal(st.tool.captured, -1);
	assert_int_equal(st.tool.event_polyp, -1);
	session_file_close(&f);
	/* format 6's: the tool, no bleeding */
	assert_int_equal(SESSION_RECORD_SIZE_6,
			 offsetof(struct session_record, tool_bleed_m3_s));
	assert_int_equal(read_sized("format=6\nrecord_size=552\n", 552,
				    SESSION_RECORD_SIZE_6, &f), 0);
	assert_int_equal(f.records[2].torn_segment, 2);
	assert_int_equal(f.records[2].tool_kind, ENDOSIM_TOOL_SNARE);
	assert_int_equal(f.records[2].tool_captured, 3);
	assert_true(f.records[2].tool_bleed_m3_s == 0);
	csv_header(&f, csv, sizeof(csv));
	assert_non_null(strstr(csv, ",patient_torn_segment,tool_kind,"));
	assert_null(strstr(csv, "tool_bleed"));
	session_file_close(&f);
	/* format 7's: the bleeding, none lying */
	assert_int_equal(SESSION_RECORD_SIZE_7,
			 offsetof(struct session_record, tool_lying_polyp));
	assert_int_equal(read_sized("format=7\nrecord_size=556\n", 556,
				    SESSION_RECORD_SIZE_7, &f), 0);
	assert_int_equal(f.records[2].tool_captured, 3);
	assert_true(f.records[2].tool_bleed_m3_s == 2e-8f);
	assert_int_equal(f.records[2].tool_lying_polyp, -1);
	session_record_to_state(&f.records[2], &st);
	assert_true(st.tool.bleed_m3_s == (double)2e-8f);
	assert_int_equal(st.tool.lying_polyp, -1);
	csv_header(&f, csv, sizeof(csv));
	assert_non_null(strstr(csv, ",tool_event_polyp,tool_bleed_m3_s"));
	assert_null(strstr(csv, "tool_lying"));
	session_file_close(&f);
	/* format 8's: a cut polyp lying, and where */
	assert_int_equal(read_sized("format=8\nrecord_size=572\n", 572, all,
				    &f), 0);
	assert_int_equal(f.records[2].tool_lying_polyp, 4);
	session_record_to_state(&f.records[2], &st);
	assert_int_equal(st.tool.lying_polyp, 4);
	assert_true(st.tool.lying_at[2] == (double)0.3f);
	csv_header(&f, csv, sizeof(csv));
	assert_non_null(strstr(csv, ",tool_bleed_m3_s,tool_lying_polyp,"
				    "tool_lying_x_m,tool_lying_y_m,"
				    "tool_lying_z_m"));
	session_file_close(&f);
	assert_int_equal(read_sized("format=1\n", 304, v1, &f), 0);
	session_file_close(&f);
	assert_int_equal(read_sized("record_size=304\n", 320, v2, &f),
			 -EPROTO);
	assert_int_equal(read_sized("record_size=296\n", 296, v1, &f),
			 -EPROTO);
	assert_int_equal(read_sized("format=1\n", 296, v1, &f), -EPROTO);
}

/* The SHAPE frames' decimation: the fewest frames that keep 30 Hz. */
static void test_shape_every(void **state)
{
	static const uint64_t periods[] = { 1000000, 500000, 250000, 2000000,
					    10000000, 30000000 };
	struct endosim_state st;

	(void)state;
	assert_int_equal(session_shape_every(1000000), 33); /* 30.3 Hz */
	for (size_t i = 0; i < sizeof(periods) / sizeof(periods[0]); i++) {
		uint64_t p = periods[i], every = session_shape_every(p);

		assert_true(ENDOSIM_NS_PER_S / (double)(every * p) >=
			    SESSION_SHAPE_HZ);
		assert_true(ENDOSIM_NS_PER_S / (double)((every + 1) * p) <
			    SESSION_SHAPE_HZ);
	}
	assert_int_equal(session_shape_every(40000000), 1); /* a 25 Hz loop */
	memset(&st, 0, sizeof(st));
	st.cycle = 66;
	assert_false(session_shape_due(&st, 33)); /* the paper model's */
	st.rod.model = ENDOSIM_MODEL_ROD;
	assert_true(session_shape_due(&st, 33));
	st.cycle = 67;
	assert_false(session_shape_due(&st, 33));
	st.cycle = 0;
	assert_true(session_shape_due(&st, 33));
}

/* A rod's state at cycle K: every value its own. */
static void rod_state(struct endosim_state *st, uint64_t k)
{
	memset(st, 0, sizeof(*st));
	st->cycle = k;
	st->stamp_ns = 1000 * k;
	st->rod.model = ENDOSIM_MODEL_ROD;
	st->rod.points = 161;
	st->rod.nodes = 5;
	st->rod.span_nodes[0] = 3;
	st->rod.span_nodes[1] = 2;
	for (int i = 0; i < 161; i++) {
		st->rod.point[i][0] = 0.01f * (float)i;
		st->rod.point[i][1] = (float)k;
		st->rod.point[i][2] = -0.5f * (float)i;
		st->rod.roll[i] = 0.001f * (float)(i + k);
	}
	/* the spans' largest: 5 mm (node 1), 13 mm (node 4) */
	memcpy(st->rod.node, (const float[5][3]){ { 0.001f, 0, 0 },
						  { 0.003f, 0.004f, 0 },
						  { 0, 0, -0.002f },
						  { 0, 0.005f, 0 },
						  { 0, 0.012f, 0.005f } },
	       5 * sizeof(st->rod.node[0]));
}

/* A session of 100 cycles of the rod, a SHAPE every 33rd, as the recorder
 * writes them; its shapes read back. */
static void write_rod_session(struct session_file *f)
{
	static struct session_shape sh;
	static unsigned char payload[sizeof(struct session_shape)];
	int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
	struct endosim_state st;
	struct session_record r;

	assert_true(fd >= 0);
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  header, strlen(header)), 0);
	for (uint64_t k = 0; k < 100; k++) {
		rod_state(&st, k);
		session_record_from_state(&st, &r);
		assert_int_equal(session_file_write_frame(
					 fd, SESSION_FRAME_RECORD, &r,
					 sizeof(r)), 0);
		if (session_shape_due(&st, 33)) {
			uint32_t n;

			session_shape_from_state(&st, &sh);
			n = session_shape_pack(&sh, payload);
			assert_int_equal(n, 40 + 161 * 16 + 5 * 12);
			assert_int_equal(session_file_write_frame(
						 fd, SESSION_FRAME_SHAPE,
						 payload, n), 0);
		}
	}
	close(fd);
	assert_int_equal(session_file_read(path, f), 0);
}

/* The shape at or before a time, as the state published it. */
static void test_shape_round_trip(void **state)
{
	static struct session_shape sh;
	struct endosim_state want, got;
	struct session_file f;

	(void)state;
	write_rod_session(&f);
	assert_int_equal(f.n_records, 100);
	assert_int_equal(f.n_shapes, 4); /* cycles 0, 33, 66, 99 */
	assert_int_equal(session_file_seek_shape(&f, 0), 0);
	assert_int_equal(session_file_seek_shape(&f, 65999), 1);
	assert_int_equal(session_file_seek_shape(&f, 66000), 2);
	assert_int_equal(session_file_seek_shape(&f, 1u << 30), 3);
	session_file_shape(&f, 2, &sh);
	assert_int_equal(sh.cycle, 66);
	assert_int_equal(sh.stamp_ns, 66000);
	rod_state(&want, 66);
	memset(&got, 0xff, sizeof(got)); /* what was shown before */
	session_shape_to_state(&sh, &got);
	assert_int_equal(got.rod.contacts, UINT32_MAX); /* a record's */
	assert_int_equal(got.rod.points, 161);
	assert_int_equal(got.rod.nodes, 5);
	assert_memory_equal(got.rod.span_nodes, want.rod.span_nodes,
			    sizeof(want.rod.span_nodes));
	/* the arrays, their unused elements zero */
	assert_memory_equal(got.rod.point, want.rod.point,
			    sizeof(want.rod.point));
	assert_memory_equal(got.rod.roll, want.rod.roll, sizeof(want.rod.roll));
	assert_memory_equal(got.rod.node, want.rod.node, sizeof(want.rod.node));
	assert_float_equal(got.scope.bow_m[0], 0.005, 1e-9);
	assert_float_equal(got.scope.bow_m[1], 0.013, 1e-9);
	assert_true(got.scope.bow_m[2] == 0 && got.scope.bow_m[3] == 0);
	session_record_to_state(&f.records[66], &got);
	assert_int_equal(got.cycle, 66);
	assert_int_equal(got.rod.model, ENDOSIM_MODEL_ROD);
	session_file_close(&f);
}

/*
 * A SHAPE frame whose counts run past its payload stops the reader as
 * damage does (its CRC is good: a writer's bug); a frame of a type this
 * reader does not know is skipped.
 */
static void test_shape_damaged(void **state)
{
	static struct session_shape sh;
	static unsigned char payload[sizeof(struct session_shape)];
	struct endosim_state st;
	struct session_record r = { .cycle = 1 };
	struct session_file f;
	int fd;
	uint32_t n;

	(void)state;
	rod_state(&st, 0);
	session_shape_from_state(&st, &sh);
	n = session_shape_pack(&sh, payload);
	fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  header, strlen(header)), 0);
	assert_int_equal(session_file_write_frame(fd, 99, "later", 5), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_SHAPE,
						  payload, n), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_SHAPE,
						  payload, n - 1), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_RECORD, &r,
						  sizeof(r)), 0);
	close(fd);
	assert_int_equal(session_file_read(path, &f), 0);
	assert_int_equal(f.n_shapes, 1);
	assert_int_equal(f.n_records, 0);
	assert_true(f.bytes_ignored == 12 + n - 1 + 12 + sizeof(r));
	session_file_close(&f);
}

/* A published state survives the round trip to float precision. */
static void test_record_state(void **state)
{
	struct endosim_state s, back;
	struct session_record r;

	(void)state;
	memset(&s, 0, sizeof(s));
	s.cycle = 123456789;
	s.stamp_ns = 987654321012ull;
	s.state = ENDOSIM_STATE_ENABLED;
	s.axis[0].position = 0.4321;
	s.axis[2].limited = -0.0987;
	s.scope.tip_s_m = 1.234;
	s.scope.dir[2] = 1;
	s.scope.bow_m[1] = 0.027;
	s.scope.spans = 2;
	s.haptics.contact = 1;
	s.haptics.trans_loop_n = 8.4;
	s.safety.ramp = 0.5;
	session_record_from_state(&s, &r);
	session_record_to_state(&r, &back);
	assert_int_equal(back.cycle, s.cycle);
	assert_int_equal(back.stamp_ns, s.stamp_ns);
	assert_int_equal(back.state, s.state);
	assert_float_equal(back.axis[0].position, 0.4321, 1e-7);
	assert_float_equal(back.axis[2].limited, -0.0987, 1e-8);
	assert_float_equal(back.scope.tip_s_m, 1.234, 1e-6);
	assert_true(back.scope.dir[2] == 1.0);
	assert_float_equal(back.scope.bow_m[1], 0.027, 1e-8);
	assert_int_equal(back.scope.spans, 2);
	assert_int_equal(back.haptics.contact, 1);
	assert_float_equal(back.haptics.trans_loop_n, 8.4, 1e-6);
	assert_true(back.safety.ramp == 0.5);
}

/* CRC-32 a bit at a time, as the standard defines it. */
static uint32_t crc_by_bits(const unsigned char *p, size_t n)
{
	uint32_t crc = ~0u;

	while (n--) {
		crc ^= *p++;
		for (int k = 0; k < 8; k++) {
			crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
		}
	}
	return ~crc;
}

/* The CRC is zlib's: the check value of "123456789", and the bitwise
 * definition's on every length and alignment around the 8-byte steps,
 * also when fed in two pieces. */
static void test_crc(void **state)
{
	unsigned char buf[80];
	uint32_t x = 12345;

	(void)state;
	assert_int_equal(session_crc32(0, "123456789", 9), 0xCBF43926u);
	assert_int_equal(session_crc32(session_crc32(0, "1234", 4), "56789",
				       5), 0xCBF43926u);
	for (size_t i = 0; i < sizeof(buf); i++) {
		x = x * 1103515245u + 12345u;
		buf[i] = (unsigned char)(x >> 16);
	}
	for (size_t at = 0; at < 8; at++) {
		for (size_t n = 0; at + n <= sizeof(buf); n++) {
			uint32_t want = crc_by_bits(buf + at, n);

			assert_int_equal(session_crc32(0, buf + at, n), want);
			assert_int_equal(session_crc32(session_crc32(0, buf + at,
								     n / 3),
						       buf + at + n / 3,
						       n - n / 3),
					 want);
		}
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_crc),
		cmocka_unit_test(test_round_trip),
		cmocka_unit_test(test_cut_everywhere),
		cmocka_unit_test(test_damage_stops),
		cmocka_unit_test(test_record_state),
		cmocka_unit_test(test_old_layout),
		cmocka_unit_test(test_shape_every),
		cmocka_unit_test(test_shape_round_trip),
		cmocka_unit_test(test_shape_damaged),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
