/*
 * endoctl_session.c - endoctl's training sessions: over the sockets, or
 * a session file read without endosimd (endoctl.h).
 */
#include "endoctl/endoctl.h"

/* ------------------------------------------------------------ sessions */

/* A session request; *REP is its OK reply. */
static int session_request(struct ctl *ctl, bool write,
			   Endosim__Request__BodyCase body, void *msg,
			   Endosim__Reply **rep)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;

	req.body_case = body;
	req.enable = msg; /* one member of the oneof's union */
	return ctl_transact(ctl, write, &req, rep);
}

static const char *session_state(const Endosim__SessionInfo *s)
{
	return s->recording ? "recording" : s->ended ? "ended" : "cut short";
}

/*
 * When an ended session ended, UTC like its start (its start plus its
 * duration), into OUT; "" while it records, when its length is not known
 * (a listing does not read the records) or the start is unreadable.
 */
static void session_ended_at(const Endosim__SessionInfo *s, char *out,
			     size_t size)
{
	struct tm tm = { 0 };
	const char *rest = strptime(s->started, "%Y-%m-%dT%H:%M:%SZ", &tm);
	time_t t;

	out[0] = '\0';
	if (s->recording || !s->records || !rest || *rest ||
	    !isfinite(s->duration_s)) {
		return;
	}
	t = timegm(&tm) + (time_t)llround(s->duration_s);
	gmtime_r(&t, &tm);
	strftime(out, size, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* The session's facts as JSON members (the object is the caller's). */
static void json_session_facts(struct json *j, const Endosim__SessionInfo *s)
{
	char ended[32];

	session_ended_at(s, ended, sizeof(ended));
	json_uint(j, "id", s->id);
	json_string(j, "trainee", s->trainee);
	json_string(j, "case", s->case_name);
	json_string(j, "started", s->started);
	json_string(j, "ended_at", ended);
	json_string(j, "state", session_state(s));
	json_bool(j, "recording", s->recording);
	json_bool(j, "ended", s->ended);
	json_double(j, "duration_s", s->duration_s);
	json_uint(j, "records", s->records);
	json_uint(j, "drops", s->drops);
	json_uint(j, "bytes", s->bytes);
	json_string(j, "path", s->path);
}

static void print_session_facts(const Endosim__SessionInfo *s)
{
	char ended[32];

	session_ended_at(s, ended, sizeof(ended));
	printf("session %" PRIu64 " (%s): trainee '%s', case %s, started %s%s%s\n"
	       "file %s, %" PRIu64 " bytes\n", s->id, session_state(s),
	       s->trainee, s->case_name, s->started, *ended ? ", ended " : "",
	       ended, s->path, s->bytes);
	if (s->recording || s->records) {
		printf("%.1f s, %" PRIu64 " records, %" PRIu64 " dropped\n",
		       s->duration_s, s->records, s->drops);
	}
}

/* The events of the patient's kinds (a turn, the hand, a valve, a
 * perforation, a tear, the sedation). */
static bool patient_kind(uint32_t kind)
{
	return kind >= SESSION_EVENT_POSITION &&
	       kind <= SESSION_EVENT_SEDATION;
}

/* The tool's (a tool handed over, a capture, a cut, ...). */
static bool tool_kind(uint32_t kind)
{
	return kind == SESSION_EVENT_TOOL;
}

/*
 * F's events of the kinds KIND says after the metrics: a line TITLE, then
 * lines "  T s  KIND  TEXT", or the JSON array KEY; nothing when it has
 * none (an older file's show reads as it did).
 */
static void print_events(const struct ctl *ctl, struct json *j,
			 const struct session_file *f, bool (*kind)(uint32_t),
			 const char *title, const char *key)
{
	uint64_t t0 = sessionview_start_ns(f);
	size_t n = 0;

	for (size_t i = 0; i < f->n_events; i++) {
		n += kind(f->events[i].ev.kind);
	}
	if (!n) {
		return;
	}
	if (ctl->json) {
		json_array_begin(j, key);
	} else {
		printf("%s\n", title);
	}
	for (size_t i = 0; i < f->n_events; i++) {
		const struct session_event *ev = &f->events[i].ev;
		double t = (double)(int64_t)(ev->stamp_ns - t0) *
			   ENDOSIM_S_PER_NS;

		if (!kind(ev->kind)) {
			continue;
		}
		if (!ctl->json) {
			printf("  %8.2f s  %-11s  %s\n", t,
			       names_event(ev->kind), f->events[i].text);
			continue;
		}
		json_object_begin(j, NULL);
		json_double(j, "t_s", t);
		json_string(j, "kind", names_event(ev->kind));
		json_int(j, "axis", ev->axis);
		json_uint(j, "detail", ev->detail);
		json_double(j, "value", ev->value);
		json_string(j, "text", f->events[i].text);
		json_object_end(j);
	}
	if (ctl->json) {
		json_array_end(j);
	}
}

/* The session, the metrics M (NULL: none) and the patient's and the
 * tool's events of its file F (NULL: not read) on stdout. */
static void print_session(const struct ctl *ctl, const Endosim__SessionInfo *s,
			  const struct metrics_result *m, const char *note,
			  const struct session_file *f)
{
	struct json j;

	json_init(&j, stdout);
	if (!ctl->json) {
		print_session_facts(s);
		if (note) {
			printf("%s\n", note);
		}
		if (m) {
			sessionview_print(stdout, m);
		}
	} else {
		json_object_begin(&j, NULL);
		json_session_facts(&j, s);
		if (note) {
			json_string(&j, "note", note);
		}
		if (m) {
			sessionview_json(&j, "metrics", m);
		}
	}
	if (f) {
		print_events(ctl, &j, f, patient_kind, "patient events",
			     "patient_events");
		print_events(ctl, &j, f, tool_kind, "tool events",
			     "tool_events");
	}
	if (ctl->json) {
		json_object_end(&j);
	}
}

static int session_start(struct ctl *ctl, int argc, char **argv)
{
	Endosim__SessionStart body = ENDOSIM__SESSION_START__INIT;
	Endosim__Reply *rep;
	int r;

	for (int i = 2; i < argc; i += 2) {
		if (i + 1 < argc && !strcmp(argv[i], "--trainee")) {
			body.trainee = argv[i + 1];
		} else if (i + 1 < argc && !strcmp(argv[i], "--case")) {
			body.case_name = argv[i + 1];
		} else if (i + 1 < argc && !strcmp(argv[i], "--sedation")) {
			body.sedation = argv[i + 1];
		} else {
			fprintf(stderr, "endoctl: session start [--trainee "
				"NAME] [--case NAME] [--sedation none|minimal|"
				"moderate|deep]\n");
			return EXIT_USAGE;
		}
	}
	r = session_request(ctl, true, ENDOSIM__REQUEST__BODY_SESSION_START,
			    &body, &rep);
	if (r) {
		return r;
	}
	print_session(ctl, rep->session->session, NULL, NULL, NULL);
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

/* Stop, status: the recorder's session with its live or final metrics. */
static int session_current(struct ctl *ctl, bool stop)
{
	Endosim__SessionStop stop_body = ENDOSIM__SESSION_STOP__INIT;
	Endosim__SessionStatus status_body = ENDOSIM__SESSION_STATUS__INIT;
	const Endosim__SessionInfo *s;
	struct metrics_result m;
	Endosim__Reply *rep;
	int r;

	r = stop ? session_request(ctl, true,
				   ENDOSIM__REQUEST__BODY_SESSION_STOP,
				   &stop_body, &rep)
		 : session_request(ctl, false,
				   ENDOSIM__REQUEST__BODY_SESSION_STATUS,
				   &status_body, &rep);
	if (r) {
		return r;
	}
	s = rep->session->session;
	if (!s) {
		printf(ctl->json ? "{\"recording\":false,\"id\":0}\n"
				 : "no session since endosimd started\n");
	} else {
		if (s->metrics) {
			sessionpb_to_metrics(s->metrics, &m);
		}
		print_session(ctl, s, s->metrics ? &m : NULL, NULL, NULL);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static void print_session_list(const struct ctl *ctl,
			       const Endosim__SessionListReply *l)
{
	struct json j;

	if (!ctl->json) {
		printf("%6s  %-20s  %-10s  %-18s  %10s  %s\n", "ID", "STARTED",
		       "STATE", "CASE", "BYTES", "TRAINEE");
		for (size_t i = 0; i < l->n_sessions; i++) {
			const Endosim__SessionInfo *s = l->sessions[i];

			printf("%6" PRIu64 "  %-20s  %-10s  %-18s  %10" PRIu64
			       "  %s\n", s->id, s->started, session_state(s),
			       s->case_name, s->bytes, s->trainee);
		}
		return;
	}
	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_string(&j, "directory", l->directory);
	json_array_begin(&j, "sessions");
	for (size_t i = 0; i < l->n_sessions; i++) {
		json_object_begin(&j, NULL);
		json_session_facts(&j, l->sessions[i]);
		json_object_end(&j);
	}
	json_array_end(&j);
	json_object_end(&j);
}

static int session_list(struct ctl *ctl)
{
	Endosim__SessionList body = ENDOSIM__SESSION_LIST__INIT;
	Endosim__Reply *rep;
	int r = session_request(ctl, false, ENDOSIM__REQUEST__BODY_SESSION_LIST,
				&body, &rep);

	if (r) {
		return r;
	}
	print_session_list(ctl, rep->session_list);
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

/*
 * A session named on the command line, its file read: by ID, with its facts
 * from endosimd; or by the path of its file (it has a '/': ./3.endoses),
 * with endosimd not asked (it may be stopped), its facts from the file as
 * endosimd would give them (sessiondir.h, sessionpb.h).
 */
struct shown {
	struct session_file f;
	const Endosim__SessionInfo *s;
	Endosim__Reply *rep;           /* by ID */
	struct sessiondir_entry entry; /* by path */
	Endosim__SessionInfo local;
};

/* R of reading the session file PATH, said on stderr; the exit status. */
static int session_file_error(const char *path, int r)
{
	fprintf(stderr, "endoctl: %s: %s\n", path, r == -EBADMSG ?
		"not a session file" : r == -EPROTO ?
		"a format this endoctl does not know" : strerror(-r));
	return EXIT_REFUSED;
}

static int session_open(struct ctl *ctl, const char *id_text, struct shown *sh)
{
	Endosim__SessionShow body = ENDOSIM__SESSION_SHOW__INIT;
	char *end;
	int r;

	if (strchr(id_text, '/')) {
		r = sessiondir_stat_file(id_text, &sh->entry);
		if (!r) {
			r = session_file_read(id_text, &sh->f);
		}
		if (r) {
			return session_file_error(id_text, r);
		}
		sessionpb_from_entry(&sh->local, &sh->entry);
		sh->local.path = (char *)id_text;
		sh->s = &sh->local;
		return 0;
	}
	body.id = strtoull(id_text, &end, 10);
	if (*end || !body.id) {
		fprintf(stderr, "endoctl: '%s' is neither a session id nor a "
			"session file's path (with a '/')\n", id_text);
		return EXIT_USAGE;
	}
	r = session_request(ctl, false, ENDOSIM__REQUEST__BODY_SESSION_SHOW,
			    &body, &sh->rep);
	if (r) {
		return r;
	}
	sh->s = sh->rep->session->session;
	r = session_file_read(sh->s->path, &sh->f);
	if (r) {
		r = session_file_error(sh->s->path, r);
		endosim__reply__free_unpacked(sh->rep, NULL);
		sh->rep = NULL;
	}
	return r;
}

static void session_close(struct shown *sh)
{
	session_file_close(&sh->f);
	if (sh->rep) {
		endosim__reply__free_unpacked(sh->rep, NULL);
	}
}

static int session_show(struct ctl *ctl, const char *id)
{
	struct shown sh = { 0 };
	Endosim__SessionInfo s;
	struct metrics_result m;
	char note[160] = "";
	bool recomputed;
	int r = session_open(ctl, id, &sh);

	if (r) {
		return r;
	}
	s = *sh.s;
	if (s.recording && s.metrics) {
		sessionpb_to_metrics(s.metrics, &m); /* live */
	} else if (sessionview_metrics(&sh.f, &m, &recomputed)) {
		fprintf(stderr, "endoctl: out of memory\n");
		r = EXIT_REFUSED;
		goto out;
	} else if (recomputed) {
		snprintf(note, sizeof(note), "no END frame (cut short, %zu "
			 "bytes after the last complete record ignored): "
			 "metrics recomputed from %zu records",
			 sh.f.bytes_ignored, sh.f.n_records);
	}
	if (!s.recording) { /* its length: the file's, as in its metrics */
		s.duration_s = m.duration_s;
		s.records = m.records;
		s.drops = m.drops;
	}
	print_session(ctl, &s, &m, *note ? note : NULL, &sh.f);
out:
	session_close(&sh);
	return r;
}

/* One summary row (sessionview.h) for session ID, its metrics as
 * `session show` gives them. */
static int summary_row(struct ctl *ctl, const char *id, FILE *out,
		       bool *werr)
{
	struct shown sh = { 0 };
	static struct metrics_result m;
	bool recomputed;
	int r = session_open(ctl, id, &sh);

	if (r) {
		return r;
	}
	r = sessionview_metrics(&sh.f, &m, &recomputed);
	if (r) {
		fprintf(stderr, "endoctl: %s: %s\n", id, strerror(-r));
	} else {
		*werr = sessionview_summary_row(out, &sh.f, &m) != 0;
	}
	session_close(&sh);
	return r ? EXIT_REFUSED : 0;
}

static int session_export(struct ctl *ctl, int argc, char **argv)
{
	const char *out_path = NULL;
	struct shown sh = { 0 };
	bool csv = false, events = false, summary = false, werr = false;
	FILE *out = stdout;
	int r = 0, ids = 0;

	for (int i = 2; i < argc; i++) {
		if (!strcmp(argv[i], "--csv")) {
			csv = true;
		} else if (!strcmp(argv[i], "--events")) {
			events = true;
		} else if (!strcmp(argv[i], "--summary")) {
			summary = true;
		} else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
			out_path = argv[++i];
		} else if (argv[i][0] != '-' && ids == i - 2) {
			ids++;
		} else {
			csv = summary = false;
			break;
		}
	}
	if (csv == summary || ids < 1 || (csv && ids != 1) ||
	    (summary && events)) {
		fprintf(stderr, "endoctl: session export ID|FILE --csv "
			"[--events] [--out FILE] | export ID|FILE... --summary "
			"[--out FILE]\n");
		return EXIT_USAGE;
	}
	if (!summary && (r = session_open(ctl, argv[2], &sh))) {
		return r; /* refused before FILE is touched */
	}
	if (out_path && !(out = fopen(out_path, "we"))) {
		fprintf(stderr, "endoctl: %s: %s\n", out_path, strerror(errno));
		if (!summary) {
			session_close(&sh);
		}
		return EXIT_REFUSED;
	}
	if (summary) {
		werr = sessionview_summary_header(out) != 0;
		for (int k = 0; k < ids && !r && !werr; k++) {
			r = summary_row(ctl, argv[2 + k], out, &werr);
		}
	} else {
		werr = (events ? sessionview_events_csv(out, &sh.f)
			       : sessionview_csv(out, &sh.f)) != 0;
		session_close(&sh);
	}
	werr |= out_path ? fclose(out) != 0 : fflush(out) != 0;
	if (werr) {
		fprintf(stderr, "endoctl: %s: write error\n",
			out_path ? out_path : "stdout");
		r = EXIT_REFUSED;
	}
	return r;
}

/*
 * The instructor's HTML report (report.h) of session ID (or FILE) into DIR;
 * with REF (NULL: none), compared with that session (an expert's).
 */
static int session_report(struct ctl *ctl, const char *id, const char *dir,
			  const char *ref)
{
	struct shown sh = { 0 }, rsh = { 0 };
	static struct metrics_result m, rm;
	struct report_reference with = { &rsh.f, &rm };
	bool recomputed, ref_recomputed;
	int r = session_open(ctl, id, &sh);

	if (r) {
		return r;
	}
	if (ref && (r = session_open(ctl, ref, &rsh))) {
		session_close(&sh);
		return r;
	}
	r = sessionview_metrics(&sh.f, &m, &recomputed);
	if (!r && ref) {
		r = sessionview_metrics(&rsh.f, &rm, &ref_recomputed);
	}
	if (!r) {
		r = report_write(&sh.f, &m, ref ? &with : NULL, dir);
	}
	if (ref) {
		session_close(&rsh);
	}
	if (r) {
		fprintf(stderr, "endoctl: report in %s: %s\n", dir,
			strerror(-r));
		r = EXIT_REFUSED;
	} else {
		printf("wrote %s/index.html%s\n", dir, recomputed ?
		       " (metrics recomputed: the file was cut short)" : "");
	}
	session_close(&sh);
	return r;
}

int ctl_cmd_session(struct ctl *ctl, int argc, char **argv)
{
	const char *sub = argc >= 2 ? argv[1] : "";

	if (!strcmp(sub, "start")) {
		return session_start(ctl, argc, argv);
	}
	if (argc == 2 && (!strcmp(sub, "stop") || !strcmp(sub, "status"))) {
		return session_current(ctl, !strcmp(sub, "stop"));
	}
	if (argc == 2 && !strcmp(sub, "list")) {
		return session_list(ctl);
	}
	if (argc == 2 && !strcmp(sub, "map")) {
		return ctl_session_map(ctl);
	}
	if (argc == 3 && !strcmp(sub, "show")) {
		return session_show(ctl, argv[2]);
	}
	if (argc >= 3 && !strcmp(sub, "export")) {
		return session_export(ctl, argc, argv);
	}
	if (argc == 5 && !strcmp(sub, "report") && !strcmp(argv[3], "--out")) {
		return session_report(ctl, argv[2], argv[4], NULL);
	}
	if (argc == 7 && !strcmp(sub, "report") && !strcmp(argv[3], "--out") &&
	    !strcmp(argv[5], "--reference")) {
		return session_report(ctl, argv[2], argv[4], argv[6]);
	}
	fprintf(stderr, "endoctl: session start [--trainee NAME] [--case NAME]"
		" [--sedation LEVEL] | stop | status | map | list | show ID | export ID --csv [--events] "
		"| export ID... --summary "
		"[--out FILE] | report ID --out DIR [--reference REF_ID] (ID: or "
		"a session file's "
		"path, read without endosimd)\n");
	return EXIT_USAGE;
}
