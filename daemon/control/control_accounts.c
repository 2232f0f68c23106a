/*
 * control_accounts.c - who sees what of the rig's records
 * (control_private.h): Login and Accounts, and the rule that every other
 * request of the records passes (accounts.h). A connection is who its
 * login says; without one, root and the command group (the rig's staff,
 * as the sockets' permissions say) are an administrator and anyone else
 * sees no records. A PIN's hash blocks the control thread for its 40 ms
 * or so: a login is one request of one client, rare, and wrong PINs in a
 * row make the next tries wait (refused unhashed), so that guessing cannot
 * keep the thread busy for one user; the force loop never waits on it.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/log.h"
#include "control/control_private.h"

struct control_accounts {
	struct accounts *db;
	Endosim__AccountsReply reply;
	Endosim__AccountUser *users;
	Endosim__AccountUser **users_p;
	Endosim__AccountGroup *groups;
	Endosim__AccountGroup **groups_p;
	char ***lines;              /* the groups' trainees and courses:
				       2 a group, each NULL-ended */
	struct accounts_user *rows;
	struct accounts_group *group_rows;
	size_t n_groups;
	char words[512];            /* a refusal's */
};

void control_accounts_path(const struct config *cfg, char *out,
			   size_t size)
{
	const char *db = cfg->records.database;
	char *slash;

	if (db[0] == '/') {
		snprintf(out, size, "%s", db);
	} else {
		snprintf(out, size, "%s/%s", cfg->session.directory, db);
	}
	slash = strrchr(out, '/');
	snprintf(slash + 1, size - (size_t)(slash + 1 - out), "%s",
		 ACCOUNTS_DEFAULT_NAME);
}

struct control_accounts *control_accounts_create(const struct config *cfg)
{
	struct control_accounts *ca = calloc(1, sizeof(*ca));
	char path[3 * CONFIG_STR];

	control_accounts_path(cfg, path, sizeof(path));
	if (!ca || !(ca->db = accounts_create(path))) {
		log_err("control: out of memory, or libsodium cannot start");
		free(ca);
		return NULL;
	}
	return ca;
}

/* What the last reply was made of. */
static void free_reply(struct control_accounts *ca)
{
	for (size_t i = 0; ca->lines && i < 2 * ca->n_groups; i++) {
		for (char **l = ca->lines[i]; l && *l; l++) {
			free(*l);
		}
		free(ca->lines[i]);
	}
	free(ca->lines);
	free(ca->users);
	free(ca->users_p);
	free(ca->groups);
	free(ca->groups_p);
	free(ca->rows);
	accounts_groups_free(ca->group_rows, ca->n_groups);
	ca->lines = NULL;
	ca->users = NULL;
	ca->users_p = NULL;
	ca->groups = NULL;
	ca->groups_p = NULL;
	ca->rows = NULL;
	ca->group_rows = NULL;
	ca->n_groups = 0;
}

void control_accounts_destroy(struct control_accounts *ca)
{
	if (!ca) {
		return;
	}
	free_reply(ca);
	accounts_destroy(ca->db);
	free(ca);
}

struct accounts *control_accounts_db(struct control *c)
{
	return c->accounts->db;
}

/* ------------------------------------------------------------ the rule */

static bool administrator(const struct client *cl)
{
	return cl->logged_in ? cl->user.role == ACCOUNTS_ADMINISTRATOR
			     : cl->staff;
}

/* "Ann (trainee)" or "not logged in" into OUT. */
static const char *who(const struct client *cl, char *out, size_t size)
{
	if (!cl->logged_in) {
		return "not logged in";
	}
	snprintf(out, size, "logged in as %s (%s)", cl->user.name,
		 accounts_role_name(cl->user.role));
	return out;
}

/* Refuses REP with WHY (then " (you are WHO)"): true. */
static bool refused(struct control *c, const struct client *cl,
		    Endosim__Reply *rep, Endosim__Status status,
		    const char *why)
{
	struct control_accounts *ca = c->accounts;
	char name[128];

	snprintf(ca->words, sizeof(ca->words), "%s (you are %s)", why,
		 who(cl, name, sizeof(name)));
	refuse(rep, status, ca->words);
	return true;
}

/* The trainees CL sees into *NAMES (NULL: every one). 0 or -errno. */
static int seen(struct control *c, const struct client *cl, char **names)
{
	bool all;
	int e;

	*names = NULL;
	if (!cl->logged_in) {
		return 0; /* staff: the rule let no one else this far */
	}
	e = accounts_seen(c->accounts->db, &cl->user, names, &all);
	if (!e && all) {
		free(*names);
		*names = NULL;
	}
	return e;
}

int control_accounts_seen(struct control *c, const struct client *cl,
			  char **names)
{
	return seen(c, cl, names);
}

static bool maintenance(Endosim__Request__BodyCase body)
{
	return body == ENDOSIM__REQUEST__BODY_RECORDS_CHECK ||
	       body == ENDOSIM__REQUEST__BODY_RECORDS_REBUILD ||
	       body == ENDOSIM__REQUEST__BODY_RECORDS_BACKUP ||
	       body == ENDOSIM__REQUEST__BODY_RECORDS_RESTORE;
}

static bool reads_records(Endosim__Request__BodyCase body)
{
	return body == ENDOSIM__REQUEST__BODY_TRAINEE_SESSIONS ||
	       body == ENDOSIM__REQUEST__BODY_SESSION_LIST ||
	       body == ENDOSIM__REQUEST__BODY_SESSION_SHOW;
}

/* A trainee named that CL does not see: refused. */
static bool named_unseen(struct control *c, const struct client *cl,
			 const char *trainee, Endosim__Reply *rep)
{
	char *names, why[256];
	bool out;

	if (!*trainee || seen(c, cl, &names)) {
		return false;
	}
	out = names && !accounts_among(names, trainee);
	free(names);
	if (out) {
		snprintf(why, sizeof(why), "%s's sessions: %s", trainee,
			 cl->user.role == ACCOUNTS_TRAINEE ?
			 "a trainee sees only their own" :
			 "not a trainee of your groups");
		return refused(c, cl, rep, ENDOSIM__STATUS__STATUS_PERMISSION,
			       why);
	}
	return false;
}

bool control_accounts_refuse(struct control *c, const struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep)
{
	if (maintenance(req->body_case) && !administrator(cl)) {
		return refused(c, cl, rep, ENDOSIM__STATUS__STATUS_PERMISSION,
			       "only an administrator checks, rebuilds, backs "
			       "up or restores the records");
	}
	if (reads_records(req->body_case) && !cl->logged_in && !cl->staff) {
		return refused(c, cl, rep, ENDOSIM__STATUS__STATUS_PERMISSION,
			       "the records need a login: endoctl --as NAME "
			       "(or root, or the command group)");
	}
	if (req->body_case == ENDOSIM__REQUEST__BODY_SESSION_START) {
		return cl->logged_in && named_unseen(c, cl,
			req->session_start->trainee, rep);
	}
	return req->body_case == ENDOSIM__REQUEST__BODY_TRAINEE_SESSIONS &&
	       named_unseen(c, cl, req->trainee_sessions->trainee, rep);
}

/*
 * The N sessions S that NAMES sees, moved to its front; how many. The
 * others are swapped behind them, not overwritten: S may be the very
 * array its rows are freed by (control_trainee.c's reply), and each row
 * must stay in it once.
 */
static size_t keep_seen(Endosim__SessionInfo **s, size_t n,
			const char *names)
{
	size_t kept = 0;

	for (size_t i = 0; i < n; i++) {
		if (accounts_among(names, s[i]->trainee)) {
			Endosim__SessionInfo *seen = s[i];

			s[i] = s[kept];
			s[kept++] = seen;
		}
	}
	return kept;
}

void control_accounts_filter(struct control *c, const struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep)
{
	char *names = NULL;
	int e;

	if (rep->status != ENDOSIM__STATUS__STATUS_OK ||
	    !reads_records(req->body_case)) {
		return;
	}
	if ((e = seen(c, cl, &names))) {
		rep->body_case = ENDOSIM__REPLY__BODY__NOT_SET;
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
		       accounts_error(c->accounts->db));
		return;
	}
	if (!names) {
		return; /* an administrator */
	}
	if (rep->body_case == ENDOSIM__REPLY__BODY_SESSION_LIST) {
		rep->session_list->n_sessions =
			keep_seen(rep->session_list->sessions,
				  rep->session_list->n_sessions, names);
	} else if (rep->body_case == ENDOSIM__REPLY__BODY_TRAINEE) {
		rep->trainee->n_sessions = keep_seen(rep->trainee->sessions,
						     rep->trainee->n_sessions,
						     names);
	} else if (!accounts_among(names, rep->session->session->trainee)) {
		rep->body_case = ENDOSIM__REPLY__BODY__NOT_SET;
		refused(c, cl, rep, ENDOSIM__STATUS__STATUS_PERMISSION,
			"that session is another trainee's");
	}
	free(names);
}

/* ------------------------------------------------------------ refresh */

/* Each connection's login whose user is not among U (N) as it logged in
 * ended. */
static void end_logins(struct control *c, const struct accounts_user *u,
		       size_t n)
{
	for (int i = 0; i < c->max_clients; i++) {
		struct client *cl = &c->clients[i];
		bool still = false;

		if (cl->fd < 0 || !cl->logged_in) {
			continue;
		}
		for (size_t k = 0; k < n && !still; k++) {
			still = !strcmp(u[k].name, cl->user.name) &&
				u[k].role == cl->user.role;
		}
		if (!still) {
			log_notice("client pid %d (uid %d): logged out: %s (%s) "
				   "is no longer a user so", (int)cl->pid,
				   (int)cl->uid, cl->user.name,
				   accounts_role_name(cl->user.role));
			cl->logged_in = false;
		}
	}
}

void control_accounts_refresh(struct control *c)
{
	struct accounts *db = c->accounts->db;
	struct accounts_user *u = NULL;
	size_t n = 0;

	if (accounts_users(db, &u, &n)) {
		log_warn("accounts: %s: whether endoview asks who is training "
			 "is not known", accounts_error(db));
		free(u);
		control_training_users(c, NULL, 0);
		return;
	}
	end_logins(c, u, n);
	control_training_users(c, u, n);
	free(u);
}

/* ------------------------------------------------------------ replies */

/*
 * The users instructor ME acts on, kept of ROWS (*N, compacted): themself,
 * the trainees of the groups they manage, and the trainees in no group
 * (whom they may join to one). 0 or -EIO.
 */
static int instructor_users(struct accounts *db, const char *me,
			    struct accounts_user *rows, size_t *n)
{
	struct accounts_group *g;
	size_t n_groups, kept = 0;
	int e = accounts_groups(db, NULL, &g, &n_groups);

	if (e) {
		return e;
	}
	for (size_t i = 0; i < *n; i++) {
		bool keep = !strcmp(rows[i].name, me), grouped = false;

		for (size_t j = 0; !keep && j < n_groups; j++) {
			if (accounts_among(g[j].trainees, rows[i].name)) {
				grouped = true;
				keep = !strcmp(g[j].instructor, me);
			}
		}
		if (keep || (rows[i].role == ACCOUNTS_TRAINEE && !grouped)) {
			rows[kept++] = rows[i];
		}
	}
	*n = kept;
	accounts_groups_free(g, n_groups);
	return 0;
}

/* The reply: who CL is, and the users and groups it may see. */
static int fill_list(struct control *c, const struct client *cl)
{
	struct control_accounts *ca = c->accounts;
	Endosim__AccountsReply *m = &ca->reply;
	size_t n = 0;
	int e = 0;

	endosim__accounts_reply__init(m);
	m->who = cl->logged_in ? (char *)cl->user.name : "";
	m->role = cl->logged_in ? (char *)accounts_role_name(cl->user.role)
				: "";
	m->staff = cl->staff;
	m->training = c->training.trainee;
	if (administrator(cl)) {
		e = accounts_users(ca->db, &ca->rows, &n);
		e = e ? e : accounts_groups(ca->db, NULL, &ca->group_rows,
					    &ca->n_groups);
	} else if (cl->logged_in && cl->user.role == ACCOUNTS_INSTRUCTOR) {
		e = accounts_groups(ca->db, cl->user.name, &ca->group_rows,
				    &ca->n_groups);
		e = e ? e : accounts_users(ca->db, &ca->rows, &n);
		e = e ? e : instructor_users(ca->db, cl->user.name, ca->rows,
					     &n);
	}
	if (e || !(ca->users = calloc(n + 1, sizeof(*ca->users))) ||
	    !(ca->users_p = calloc(n + 1, sizeof(*ca->users_p)))) {
		return e ? e : -ENOMEM;
	}
	for (size_t i = 0; i < n; i++) {
		endosim__account_user__init(&ca->users[i]);
		ca->users[i].name = ca->rows[i].name;
		ca->users[i].role = (char *)accounts_role_name(ca->rows[i]
							       .role);
		ca->users_p[i] = &ca->users[i];
	}
	m->n_users = n;
	m->users = ca->users_p;
	return 0;
}

/* TEXT's lines as a repeated string into *OUT, *N (their storage kept in
 * *LINE). */
static int split_lines(char *text, char ***line, char ***out, size_t *n)
{
	size_t k = 0;

	*n = 0;
	*out = NULL;
	for (char *p = text; *p; p++) {
		k += *p == '\n';
	}
	k += *text != '\0';
	if (!(*line = calloc(k + 1, sizeof(**line)))) {
		return -ENOMEM;
	}
	*out = *line;
	for (char *p = text, *end; *text && p; p = end ? end + 1 : NULL) {
		end = strchr(p, '\n');
		if (!((*line)[(*n)++] = strndup(p, end ? (size_t)(end - p)
						       : strlen(p)))) {
			return -ENOMEM;
		}
	}
	return 0;
}

static int fill_groups(struct control_accounts *ca)
{
	size_t n = ca->n_groups;
	int e = 0;

	ca->groups = calloc(n + 1, sizeof(*ca->groups));
	ca->groups_p = calloc(n + 1, sizeof(*ca->groups_p));
	ca->lines = calloc(2 * n + 1, sizeof(*ca->lines));
	if (!ca->groups || !ca->groups_p || !ca->lines) {
		return -ENOMEM;
	}
	for (size_t i = 0; !e && i < n; i++) {
		Endosim__AccountGroup *g = &ca->groups[i];
		char **t = NULL, **k = NULL;

		endosim__account_group__init(g);
		g->name = ca->group_rows[i].name;
		g->instructor = ca->group_rows[i].instructor;
		e = split_lines(ca->group_rows[i].trainees, &t, &g->trainees,
				&g->n_trainees);
		ca->lines[2 * i] = t;
		e = e ? e : split_lines(ca->group_rows[i].courses, &k,
					&g->courses, &g->n_courses);
		ca->lines[2 * i + 1] = k;
		ca->groups_p[i] = g;
	}
	ca->reply.n_groups = n;
	ca->reply.groups = ca->groups_p;
	return e;
}

static void accounts_reply(struct control *c, const struct client *cl,
			   Endosim__Reply *rep)
{
	struct control_accounts *ca = c->accounts;
	int e = fill_list(c, cl);

	e = e ? e : fill_groups(ca);
	if (e) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
		       e == -ENOMEM ? "out of memory"
				    : accounts_error(ca->db));
		return;
	}
	rep->body_case = ENDOSIM__REPLY__BODY_ACCOUNTS;
	rep->accounts = &ca->reply;
}

/* ------------------------------------------------------------ requests */

void control_on_login(struct control *c, struct client *cl,
		      const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_accounts *ca = c->accounts;
	const Endosim__Login *m = req->login;
	struct accounts_user u;
	struct timespec now;
	double wait_s;
	int e;

	free_reply(ca);
	if (control_training_refused(c, cl, m, NULL, rep)) {
		return;
	}
	clock_gettime(CLOCK_REALTIME, &now);
	e = accounts_login(ca->db, m->name, m->pin, (double)now.tv_sec +
			   1e-9 * (double)now.tv_nsec, &u, &wait_s);
	if (e == -EACCES) {
		static struct log_ratelimit rl = LOG_RATELIMIT_INIT(10, 5);

		log_ratelimited(&rl, LOG_NOTICE, "login as %s from uid %d "
				"(pid %d): wrong name or PIN", m->name,
				(int)cl->uid, (int)cl->pid);
		snprintf(ca->words, sizeof(ca->words), "wrong name or PIN%s",
			 wait_s > 0 ? ": wrong PINs in a row, the next try "
			 "waits" : "");
		refuse(rep, ENDOSIM__STATUS__STATUS_PERMISSION, ca->words);
		return;
	}
	if (e) {
		snprintf(ca->words, sizeof(ca->words), "%s",
			 accounts_error(ca->db));
		refuse(rep, e == -EAGAIN ? ENDOSIM__STATUS__STATUS_REFUSED
					 : ENDOSIM__STATUS__STATUS_INTERNAL,
		       ca->words);
		return;
	}
	if (control_training_refused(c, cl, m, &u, rep)) {
		return;
	}
	cl->user = u;
	cl->logged_in = true;
	log_info("client pid %d (uid %d): logged in as %s (%s)", (int)cl->pid,
		 (int)cl->uid, u.name, accounts_role_name(u.role));
	accounts_reply(c, cl, rep);
}

/* An Accounts change M carried out: 0 or as accounts.h's. */
static int change(struct accounts *db, const Endosim__Accounts *m)
{
	enum accounts_role role;

	switch (m->op) {
	case ENDOSIM__ACCOUNTS__OP__OP_USER_ADD:
		return accounts_role_parse(m->role, &role) ? -EDOM :
			accounts_user_add(db, m->name, role, m->pin);
	case ENDOSIM__ACCOUNTS__OP__OP_USER_REMOVE:
		return accounts_user_remove(db, m->name);
	case ENDOSIM__ACCOUNTS__OP__OP_USER_PIN:
		return accounts_user_pin(db, m->name, m->pin);
	case ENDOSIM__ACCOUNTS__OP__OP_GROUP_ADD:
		return accounts_group_add(db, m->group, m->name);
	case ENDOSIM__ACCOUNTS__OP__OP_GROUP_REMOVE:
		return accounts_group_remove(db, m->group);
	case ENDOSIM__ACCOUNTS__OP__OP_GROUP_JOIN:
	case ENDOSIM__ACCOUNTS__OP__OP_GROUP_LEAVE:
		return accounts_group_member(db, m->group, m->name, m->op ==
					     ENDOSIM__ACCOUNTS__OP__OP_GROUP_JOIN);
	case ENDOSIM__ACCOUNTS__OP__OP_GROUP_ASSIGN:
	case ENDOSIM__ACCOUNTS__OP__OP_GROUP_UNASSIGN:
		return accounts_group_course(db, m->group, m->course, m->op ==
					     ENDOSIM__ACCOUNTS__OP__OP_GROUP_ASSIGN);
	default:
		return -ENOSYS;
	}
}

/* The change M as accounts.h's CH (its texts M's): 0, or -ENOSYS. */
static int change_of(const Endosim__Accounts *m, struct accounts_change *ch)
{
	static const enum accounts_op ops[] = {
		[ENDOSIM__ACCOUNTS__OP__OP_USER_ADD] = ACCOUNTS_USER_ADD,
		[ENDOSIM__ACCOUNTS__OP__OP_USER_REMOVE] = ACCOUNTS_USER_REMOVE,
		[ENDOSIM__ACCOUNTS__OP__OP_USER_PIN] = ACCOUNTS_USER_PIN,
		[ENDOSIM__ACCOUNTS__OP__OP_GROUP_ADD] = ACCOUNTS_GROUP_ADD,
		[ENDOSIM__ACCOUNTS__OP__OP_GROUP_REMOVE] =
			ACCOUNTS_GROUP_REMOVE,
		[ENDOSIM__ACCOUNTS__OP__OP_GROUP_JOIN] = ACCOUNTS_GROUP_JOIN,
		[ENDOSIM__ACCOUNTS__OP__OP_GROUP_LEAVE] = ACCOUNTS_GROUP_LEAVE,
		[ENDOSIM__ACCOUNTS__OP__OP_GROUP_ASSIGN] =
			ACCOUNTS_GROUP_ASSIGN,
		[ENDOSIM__ACCOUNTS__OP__OP_GROUP_UNASSIGN] =
			ACCOUNTS_GROUP_UNASSIGN,
	};

	if (m->op < ENDOSIM__ACCOUNTS__OP__OP_USER_ADD ||
	    m->op > ENDOSIM__ACCOUNTS__OP__OP_GROUP_UNASSIGN) {
		return -ENOSYS;
	}
	*ch = (struct accounts_change){ .op = ops[m->op], .name = m->name,
					.pin = m->pin, .group = m->group,
					.course = m->course };
	if (accounts_role_parse(m->role, &ch->role)) {
		ch->role = ACCOUNTS_ADMINISTRATOR; /* judged as the most */
	}
	return 0;
}

/* Whether CL may make the change M (accounts_may()), else REP refused:
 * true. */
static bool change_refused(struct control *c, const struct client *cl,
			   const Endosim__Accounts *m, Endosim__Reply *rep)
{
	bool own_pin = m->op == ENDOSIM__ACCOUNTS__OP__OP_USER_PIN &&
		       cl->logged_in && !strcmp(m->name, cl->user.name);
	struct accounts_change ch;
	int e;

	if (own_pin) {
		return false;
	}
	if (!cl->rw) {
		refuse(rep, ENDOSIM__STATUS__STATUS_READ_ONLY,
		       "read-only socket: use the control socket");
		return true;
	}
	if (administrator(cl) || change_of(m, &ch)) {
		return false; /* no such op: change() says so */
	}
	if (!cl->logged_in) {
		return refused(c, cl, rep, ENDOSIM__STATUS__STATUS_PERMISSION,
			       "only an administrator changes the accounts");
	}
	if ((e = accounts_may(c->accounts->db, &cl->user, &ch)) == -EPERM) {
		return refused(c, cl, rep, ENDOSIM__STATUS__STATUS_PERMISSION,
			       accounts_error(c->accounts->db));
	}
	if (e) {
		snprintf(c->accounts->words, sizeof(c->accounts->words), "%s",
			 accounts_error(c->accounts->db));
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
		       c->accounts->words);
		return true;
	}
	return false;
}

void control_on_accounts(struct control *c, struct client *cl,
			 const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_accounts *ca = c->accounts;
	const Endosim__Accounts *m = req->accounts;
	int e;

	free_reply(ca);
	if (m->op != ENDOSIM__ACCOUNTS__OP__OP_LIST) {
		if (change_refused(c, cl, m, rep) ||
		    control_course_refused(c, m, rep)) {
			return;
		}
		if ((e = change(ca->db, m))) {
			snprintf(ca->words, sizeof(ca->words), "%s", e == -EDOM ?
				 "a role: trainee, instructor or administrator"
				 : e == -ENOSYS ? "no such accounts operation"
				 : accounts_error(ca->db));
			refuse(rep, e == -EIO || e == -ENOMEM ?
			       ENDOSIM__STATUS__STATUS_INTERNAL :
			       ENDOSIM__STATUS__STATUS_BAD_VALUE, ca->words);
			return;
		}
		log_notice("accounts: %s %s%s%s by uid %d%s%s",
			   protobuf_c_enum_descriptor_get_value(
				   &endosim__accounts__op__descriptor,
				   m->op)->name, m->name, *m->group ? " in " :
			   "", m->group, (int)cl->uid, cl->logged_in ?
			   " as " : "", cl->logged_in ? cl->user.name : "");
		control_accounts_refresh(c);
		control_records_poke_centre(c);
	}
	accounts_reply(c, cl, rep);
}
