/*
 * endoctl_accounts.c - who sees what (endoctl.h): --as NAME's login
 * (proto's Login, on each connection), `endoctl user ...`, `endoctl group
 * ...` and `endoctl whoami` (Accounts: its list on the read-only socket,
 * its changes on the read-write one, or a user's own PIN on either). The
 * rules are endosimd's (daemon/control/control_accounts.c); a PIN read
 * here goes to it over the local socket and nowhere else.
 */
#include <fcntl.h>
#include <termios.h>

#include "endoctl/endoctl.h"

#define USER_USAGE "endoctl user list | add NAME --role trainee|instructor|" \
	"administrator | remove NAME | pin NAME\n"
#define GROUP_USAGE "endoctl group list | add GROUP --instructor NAME | " \
	"remove GROUP | join GROUP TRAINEE... | leave GROUP TRAINEE... | " \
	"assign GROUP COURSE | unassign GROUP COURSE\n"

/* One line from the terminal, unechoed, into OUT. 0 or -1. */
static int read_tty(const char *prompt, char *out, size_t size)
{
	struct termios old, quiet;
	int fd = open("/dev/tty", O_RDWR | O_CLOEXEC), r = -1;
	FILE *tty = fd >= 0 ? fdopen(fd, "r+") : NULL;

	if (!tty) {
		if (fd >= 0) {
			close(fd);
		}
		return -1;
	}
	fputs(prompt, tty);
	fflush(tty);
	if (!tcgetattr(fd, &old)) {
		quiet = old;
		quiet.c_lflag &= ~(tcflag_t)ECHO;
		tcsetattr(fd, TCSAFLUSH, &quiet);
		if (fgets(out, (int)size, tty)) {
			out[strcspn(out, "\n")] = '\0';
			r = 0;
		}
		tcsetattr(fd, TCSAFLUSH, &old);
		fputc('\n', tty);
	}
	fclose(tty);
	return r;
}

int ctl_read_pin(const char *var, const char *prompt, bool ask_twice,
		 char *pin, size_t size)
{
	const char *env = getenv(var);
	char again[128];

	if (env) {
		snprintf(pin, size, "%s", env);
		return 0;
	}
	if (read_tty(prompt, pin, size)) {
		fprintf(stderr, "endoctl: no PIN: set $%s, or run endoctl on a "
			"terminal\n", var);
		return EXIT_USAGE;
	}
	if (ask_twice && (read_tty("again: ", again, sizeof(again)) ||
			  strcmp(pin, again))) {
		fprintf(stderr, "endoctl: the two PINs differ\n");
		return EXIT_USAGE;
	}
	return 0;
}

int ctl_login(struct ctl *ctl)
{
	Endosim__Login body = ENDOSIM__LOGIN__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	char prompt[160];
	int r;

	snprintf(prompt, sizeof(prompt), "PIN of %s: ", ctl->as);
	if (!ctl->pin[0] && (r = ctl_read_pin("ENDOSIM_PIN", prompt, false,
					      ctl->pin, sizeof(ctl->pin)))) {
		return r;
	}
	body.name = (char *)ctl->as;
	body.pin = ctl->pin;
	req.body_case = ENDOSIM__REQUEST__BODY_LOGIN;
	req.login = &body;
	if ((r = ctl_request(ctl, &req, &rep))) {
		return r;
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

/* ------------------------------------------------------------ printing */

static void json_strings(struct json *j, const char *key, char **s,
			 size_t n)
{
	json_array_begin(j, key);
	for (size_t i = 0; i < n; i++) {
		json_string(j, NULL, s[i]);
	}
	json_array_end(j);
}

static void json_accounts(const Endosim__AccountsReply *m)
{
	struct json j;

	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_string(&j, "who", m->who);
	json_string(&j, "role", m->role);
	json_bool(&j, "staff", m->staff);
	json_string(&j, "training", m->training);
	json_array_begin(&j, "users");
	for (size_t i = 0; i < m->n_users; i++) {
		json_object_begin(&j, NULL);
		json_string(&j, "name", m->users[i]->name);
		json_string(&j, "role", m->users[i]->role);
		json_object_end(&j);
	}
	json_array_end(&j);
	json_array_begin(&j, "groups");
	for (size_t i = 0; i < m->n_groups; i++) {
		const Endosim__AccountGroup *g = m->groups[i];

		json_object_begin(&j, NULL);
		json_string(&j, "name", g->name);
		json_string(&j, "instructor", g->instructor);
		json_strings(&j, "trainees", g->trainees, g->n_trainees);
		json_strings(&j, "courses", g->courses, g->n_courses);
		json_object_end(&j);
	}
	json_array_end(&j);
	json_object_end(&j);
}

static void print_whoami(const Endosim__AccountsReply *m)
{
	if (*m->who) {
		printf("%s (%s)\n", m->who, m->role);
	} else {
		printf("not logged in%s\n", m->staff ? ": root or the endosim "
		       "group, an administrator" : ": no records to see");
	}
	if (*m->training) {
		printf("%s trains at the rig\n", m->training);
	}
}

static void print_users(const Endosim__AccountsReply *m)
{
	printf("%-24s %s\n", "USER", "ROLE");
	for (size_t i = 0; i < m->n_users; i++) {
		printf("%-24s %s\n", m->users[i]->name, m->users[i]->role);
	}
}

static void print_names(const char *label, char **s, size_t n)
{
	printf("  %s:", label);
	for (size_t i = 0; i < n; i++) {
		printf("%s %s", i ? "," : "", s[i]);
	}
	printf("%s\n", n ? "" : " none");
}

static void print_groups(const Endosim__AccountsReply *m)
{
	for (size_t i = 0; i < m->n_groups; i++) {
		const Endosim__AccountGroup *g = m->groups[i];

		printf("%s, managed by %s\n", g->name, g->instructor);
		print_names("trainees", g->trainees, g->n_trainees);
		print_names("courses", g->courses, g->n_courses);
	}
}

/* ------------------------------------------------------------ requests */

/* BODY sent (a change: on the read-write socket, unless OWN_PIN);
 * PRINT its reply. */
static int accounts(struct ctl *ctl, Endosim__Accounts *body, bool own_pin,
		    void (*print)(const Endosim__AccountsReply *))
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	bool change = body->op != ENDOSIM__ACCOUNTS__OP__OP_LIST;
	Endosim__Reply *rep;
	int r;

	req.body_case = ENDOSIM__REQUEST__BODY_ACCOUNTS;
	req.accounts = body;
	if ((r = ctl_transact(ctl, change && !own_pin, &req, &rep))) {
		return r;
	}
	if (ctl->json) {
		json_accounts(rep->accounts);
	} else if (print) {
		print(rep->accounts);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

int ctl_cmd_whoami(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Accounts body = ENDOSIM__ACCOUNTS__INIT;

	(void)argv;
	if (argc != 1) {
		fputs("usage: endoctl whoami\n", stderr);
		return EXIT_USAGE;
	}
	return accounts(ctl, &body, false, print_whoami);
}

/* `user add NAME --role R` into BODY (its PIN into PIN). */
static int user_add(int argc, char **argv, Endosim__Accounts *body,
		    char *pin, size_t size)
{
	if (argc != 5 || strcmp(argv[3], "--role")) {
		fputs("usage: " USER_USAGE, stderr);
		return EXIT_USAGE;
	}
	body->op = ENDOSIM__ACCOUNTS__OP__OP_USER_ADD;
	body->role = argv[4];
	return ctl_read_pin("ENDOSIM_NEW_PIN", "new PIN: ", true, pin, size);
}

int ctl_cmd_user(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Accounts body = ENDOSIM__ACCOUNTS__INIT;
	const char *verb = argc > 1 ? argv[1] : "";
	char pin[128] = "";
	int r = 0;

	body.name = argc > 2 ? argv[2] : "";
	body.pin = pin;
	if (!strcmp(verb, "list") && argc == 2) {
		return accounts(ctl, &body, false, print_users);
	} else if (!strcmp(verb, "add")) {
		r = user_add(argc, argv, &body, pin, sizeof(pin));
	} else if (!strcmp(verb, "remove") && argc == 3) {
		body.op = ENDOSIM__ACCOUNTS__OP__OP_USER_REMOVE;
	} else if (!strcmp(verb, "pin") && argc == 3) {
		body.op = ENDOSIM__ACCOUNTS__OP__OP_USER_PIN;
		r = ctl_read_pin("ENDOSIM_NEW_PIN", "new PIN: ", true, pin,
				 sizeof(pin));
	} else {
		fputs("usage: " USER_USAGE, stderr);
		return EXIT_USAGE;
	}
	return r ? r : accounts(ctl, &body, body.op ==
				ENDOSIM__ACCOUNTS__OP__OP_USER_PIN && ctl->as &&
				!strcmp(ctl->as, body.name), NULL);
}

/* `group join|leave GROUP TRAINEE...`: each trainee in turn. */
static int each_trainee(struct ctl *ctl, Endosim__Accounts *body, int argc,
			char **argv)
{
	int r = 0;

	for (int i = 3; !r && i < argc; i++) {
		body->name = argv[i];
		r = accounts(ctl, body, false, NULL);
	}
	return r;
}

/* A course as assigned: a name (endosimd's courses' directory), or a path,
 * made absolute here (endosimd's working directory is not ours). BUF:
 * PATH_MAX bytes at least. */
static const char *course_arg(const char *course, char *buf, size_t size)
{
	char cwd[4096];

	if (!strchr(course, '/') || course[0] == '/') {
		return course; /* a name, or absolute */
	}
	if (realpath(course, buf)) {
		return buf;
	}
	if (!getcwd(cwd, sizeof(cwd))) {
		return course;
	}
	snprintf(buf, size, "%s/%s", cwd, course);
	return buf;
}

int ctl_cmd_group(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Accounts body = ENDOSIM__ACCOUNTS__INIT;
	const char *verb = argc > 1 ? argv[1] : "";
	bool join = !strcmp(verb, "join"), assign = !strcmp(verb, "assign");
	char path[8192];

	body.group = argc > 2 ? argv[2] : "";
	if (!strcmp(verb, "list") && argc == 2) {
		return accounts(ctl, &body, false, print_groups);
	} else if (!strcmp(verb, "add") && argc == 5 &&
		   !strcmp(argv[3], "--instructor")) {
		body.op = ENDOSIM__ACCOUNTS__OP__OP_GROUP_ADD;
		body.name = argv[4];
	} else if (!strcmp(verb, "remove") && argc == 3) {
		body.op = ENDOSIM__ACCOUNTS__OP__OP_GROUP_REMOVE;
	} else if ((join || !strcmp(verb, "leave")) && argc >= 4) {
		body.op = join ? ENDOSIM__ACCOUNTS__OP__OP_GROUP_JOIN
			       : ENDOSIM__ACCOUNTS__OP__OP_GROUP_LEAVE;
		return each_trainee(ctl, &body, argc, argv);
	} else if ((assign || !strcmp(verb, "unassign")) && argc == 4) {
		body.op = assign ? ENDOSIM__ACCOUNTS__OP__OP_GROUP_ASSIGN
				 : ENDOSIM__ACCOUNTS__OP__OP_GROUP_UNASSIGN;
		body.course = (char *)course_arg(argv[3], path, sizeof(path));
	} else {
		fputs("usage: " GROUP_USAGE, stderr);
		return EXIT_USAGE;
	}
	return accounts(ctl, &body, false, NULL);
}
