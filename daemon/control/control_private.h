/*
 * control_private.h - what the parts of the control thread share: the
 * clients, the thread's state and the handlers' signature (control.c:
 * sockets, clients, dispatch, the thread). Each family of handlers keeps
 * the storage its replies point into, made with the control and freed
 * with it: control_reply.c status, stats, configuration, commands, the
 * hand, subscriptions and test commands; control_case.c the scene and the
 * cases; control_session.c training sessions and their live map;
 * control_trainee.c a trainee's sessions from the rig's records (the
 * courses of their groups: control_courses.c); control_training.c who
 * trains at the rig; control_guide.c guided replay; control_patient.c
 * the patient's
 * commands, control_tool.c the tool's selection (their refusals' words
 * in struct control's refusal). Control
 * thread only, as all of control.h's work.
 */
#ifndef ENDOSIM_CONTROL_PRIVATE_H
#define ENDOSIM_CONTROL_PRIVATE_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <sys/types.h>
#include <sys/un.h>

#include "control/control.h"
#include "proto/endosim.pb-c.h"
#include "proto/frame.h"
#include "control/training.h"
#include "session/accounts.h"
#include "session/records.h"

#define COMMAND_TIMEOUT_MS 200 /* the loop takes a command within this */

struct client {
	int fd;               /* -1: free slot */
	bool rw;              /* connected to the read-write socket */
	bool may_command;     /* rw, and root or in the command group */
	bool staff;           /* root or in the command group, either socket:
				 an administrator while not logged in */
	bool logged_in;       /* Login: as user */
	struct accounts_user user;
	uid_t uid;
	pid_t pid;
	uint64_t last_rx_ns;  /* last bytes received */
	uint64_t partial_ns;  /* since when part of a request waits, 0: none */
	struct frame_rx rx;
	uint8_t *out;         /* replies not yet sent */
	size_t out_len, out_cap;
	uint64_t push_period_ns; /* 0: not subscribed */
	uint64_t next_push_ns;
	uint32_t push_seq;
};

/* The families' storage (their .c files'). */
struct control_replies;
struct control_cases;
struct control_sessions;
struct control_trainees;
struct control_guide;
struct control_accounts;

struct control {
	struct config cfg;       /* the master copy */
	struct control_deps deps;
	char ro_path[sizeof(((struct sockaddr_un *)0)->sun_path)];
	char rw_path[sizeof(((struct sockaddr_un *)0)->sun_path)];
	int ro_fd, rw_fd, ep, wake_fd;
	struct client *clients;
	int max_clients;
	size_t max_request;
	size_t max_queued;
	gid_t command_gid;       /* who may command besides root */
	struct control_replies *replies;
	struct control_cases *cases;
	struct control_sessions *sessions;
	struct control_trainees *trainees;
	struct control_guide *guide;
	struct control_records *records;
	struct control_accounts *accounts;
	struct training training; /* who trains at the rig */
	Endosim__AccountsReply logout; /* Logout's reply */
	struct colon *colon;     /* the loop's now: read its mesh only */
	char case_path[2 * CONFIG_STR + 8]; /* the file it was built from */
	uint64_t scene_id;       /* its GetScene id */
	uint64_t rate_t0_ns, rate_cycle0;
	double loop_hz;
	pthread_t thread;
	bool running;
	_Atomic bool alive;
	_Atomic bool stop;
	bool end;                /* a test command: the thread ends */
	char refusal[512];       /* a refusal put in words, for its reply */
};

typedef void handler_fn(struct control *c, struct client *cl,
			const Endosim__Request *req, Endosim__Reply *rep);

/* Answers REP with STATUS and WHY (a constant string, or the family's). */
static inline void refuse(Endosim__Reply *rep, Endosim__Status status,
			  const char *why)
{
	rep->status = status;
	rep->error = (char *)why;
}

/*
 * Each family's storage: NULL on ENOMEM (logged by the caller); destroy
 * frees it and what its last reply was made of; NULL is fine.
 */
struct control_replies *control_replies_create(void);
void control_replies_destroy(struct control_replies *rb);
struct control_cases *control_cases_create(void);
void control_cases_destroy(struct control_cases *cs);
struct control_sessions *control_sessions_create(void);
void control_sessions_destroy(struct control_sessions *rb);
struct control_trainees *control_trainees_create(void);
void control_trainees_destroy(struct control_trainees *rb);
struct control_guide *control_guide_create(void);
void control_guide_destroy(struct control_guide *g);

/*
 * The rig's records (records.h) of CFG's session directory, brought up to
 * date with its files, and their centre's worker when there is one
 * (WAKE_FD: the control thread's eventfd, written when the worker copied
 * the centre's people); NULL on ENOMEM or a database of a newer schema
 * (logged: endosimd does not start).
 */
struct control_records *control_records_create(const struct config *cfg,
					       int wake_fd);
void control_records_destroy(struct control_records *cr);

/* The session RI ended: its file written to the records (its checksum
 * the recorder's when it knows it; a failure logged: the next start-up
 * writes it), and queued for the centre when there is one. Blocks on the
 * disk; the control thread. */
void control_records_ended(struct control *c, const struct recorder_info *ri);

/*
 * A training centre's PostgreSQL ([records] centre, centre.h), fed by a
 * worker thread of its own (control_centre.c): the control thread never
 * waits on the network (a centre that does not answer would stall every
 * client), and the force loop never touches it. The worker sends the
 * sessions queued in the rig's records (records.h) in their order, then
 * the changes queued in the rig's accounts (accounts.h), then copies the
 * centre's people into the rig's accounts when they changed: at start,
 * when poked, and every [records] centre_retry_s (each try waits at most
 * CENTRE_CONNECT_TIMEOUT_S to connect; main.c refused a URL that libpq
 * cannot read at start-up). After each copy of the people it writes 1 to
 * WAKE_FD (-1: none). NULL on ENOMEM (logged: endosimd does not start).
 * Destroy waits for what is being sent (at most the connect timeout, or
 * the server's answer).
 */
struct control_centre;
struct control_centre *control_centre_create(const struct config *cfg,
					     int wake_fd);
void control_centre_destroy(struct control_centre *cc);
/* Sessions or changes of the accounts were queued (a session's end, a
 * rebuild, a user or group changed): the worker sends them now. Any
 * thread. */
void control_centre_poke(struct control_centre *cc);
/* The same for the control's centre, when it has one. Control thread. */
void control_records_poke_centre(struct control *c);
/* How many times the worker copied the centre's people into the rig's
 * accounts. Any thread. */
unsigned control_centre_copies(struct control_centre *cc);
/* Whether the control's centre copied the people since the last call
 * (false without a centre). Control thread. */
bool control_records_people_copied(struct control *c);

/*
 * The sessions of the records as a reply's SessionInfos, by ID: TRAINEE's
 * alone (NULL: everyone's), each with its facts (sessionpb_from_entry()),
 * with WHAT RECORDS_MEASURES its measures' scalars in metrics (absent
 * when it has none; only those KEYS names, when not NULL), with PATHS its file's path. Each row is malloc'd
 * alone (its info first: what the infos point into never moves); free
 * them with control_rows_free().
 */
struct control_rows {
	Endosim__SessionInfo **infos;
	size_t n, cap;
	bool paths;
	unsigned what;
	const char *const *keys;  /* the measures alone (records_each()) */
	size_t n_keys;
	const char *dir;
};

/* The rows ROWS asks for (its n, infos filled): 0, or -errno with why in
 * ERROR (SIZE), logged, and no rows. */
int control_records_rows(struct control *c, const char *trainee,
			 struct control_rows *rows, char *error, size_t size);
void control_rows_free(struct control_rows *rows);

/*
 * Who sees what (control_accounts.c, accounts.h): the accounts beside
 * CFG's records; NULL on ENOMEM or libsodium failing (logged).
 */
struct control_accounts *control_accounts_create(const struct config *cfg);
void control_accounts_destroy(struct control_accounts *ca);
/* The accounts' database of CFG (beside its records) into OUT. */
void control_accounts_path(const struct config *cfg, char *out,
			   size_t size);

/*
 * Before REQ's handler: true when CL may not make it, REP refused in words
 * (the records' maintenance needs an administrator; the records' lists a
 * login, root or the command group; a trainee named, and a session's
 * trainee at its start, must be one the login sees). After it: the records in REP that CL's login does not see
 * left out (a session shown: refused).
 */
bool control_accounts_refuse(struct control *c, const struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep);
void control_accounts_filter(struct control *c, const struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep);
/* The accounts' database (accounts.h), for the families that read it. */
struct accounts *control_accounts_db(struct control *c);
/* The trainees CL sees, one a line, into *NAMES (malloc'd; NULL: every
 * one, as the staff or an administrator). 0 or -errno. */
int control_accounts_seen(struct control *c, const struct client *cl,
			  char **names);

/*
 * The courses assigned to the trainees' groups (control_courses.c),
 * which judge their sessions. A course as assigned names its file: a
 * path (with a '/') as it is, else NAME (".course" added when missing)
 * in the courses' directory, `courses` beside [case] directory (the
 * installed courses beside the installed cases; config/courses/ in a
 * checkout). 0 or -ENAMETOOLONG.
 */
int control_course_file(const struct control *c, const char *course,
			char *path, size_t size);

/* Before an Accounts change M: a course assigned whose file does not load
 * is refused (true), REP saying why (its FILE:LINE), nothing changed. */
bool control_course_refused(struct control *c, const Endosim__Accounts *m,
			    Endosim__Reply *rep);

/* The courses of a TraineeReply and what they point into. */
struct control_courses {
	Endosim__TraineeCourse *entries;
	Endosim__TraineeCourse **entries_p;
	size_t n;
	struct accounts_group *groups; /* the entries' group names */
	size_t n_groups;
};

/*
 * Each course assigned to a group of a trainee CL sees (TRAINEE's alone
 * unless ""), by group, trainee and course, into CC; each file loaded,
 * the keys of the measures its requirements name added to KEYS (*N of
 * MAX, each once). 0; -EINVAL or -errno of a course that does not load
 * (WHY, SIZE: its group and FILE:LINE); -EIO, -ENOMEM (WHY says). Free
 * CC with control_courses_free() (also after a failure).
 */
int control_courses_build(struct control *c, const struct client *cl,
			  const char *trainee, struct control_courses *cc,
			  const char **keys, size_t *n, size_t max, char *why,
			  size_t size);
void control_courses_free(struct control_courses *cc);
/* KEY added to KEYS (*N of MAX) unless it is there, or there is no room. */
void control_key_add(const char **keys, size_t *n, size_t max,
		     const char *key);

/*
 * After a change of the accounts (a change on this rig, a copy of the
 * centre's people) and at start-up: the users read once, and what hangs
 * on them looked at again: each connection's login, whose user is gone
 * or has another role now, ended (logged); who trains at the rig
 * (control_training_users()). A failed read logged, nothing ended.
 */
void control_accounts_refresh(struct control *c);

/*
 * Who trains at the rig (control_training.c, training.h) on the users U
 * (N of them; U NULL: not known): whether the accounts hold a trainee,
 * and whether the rig's trainee is still one (no longer: nobody trains).
 */
void control_training_users(struct control *c,
			    const struct accounts_user *u, size_t n);

/*
 * A Login M that asks to train at the rig (else false at once): before
 * the PIN's hash (U NULL) whether what it names alone is refused (not
 * the control socket's staff, another's session recording); after it
 * (U the user logged in), U made the rig's trainee, or refused. true:
 * refused, REP says why, nothing changed.
 */
bool control_training_refused(struct control *c, const struct client *cl,
			      const Endosim__Login *m,
			      const struct accounts_user *u,
			      Endosim__Reply *rep);

/* The trainee of a session CL starts naming NAMED ("" none) into OUT
 * (SIZE bytes): 0, or -1 refused (REP says why). */
int control_training_session(struct control *c, const struct client *cl,
			     const char *named, char *out, size_t size,
			     Endosim__Reply *rep);

/* The requests, by family (see above). */
handler_fn control_on_get_status;
handler_fn control_on_get_stats;
handler_fn control_on_get_config;
handler_fn control_on_set_param;
handler_fn control_on_enable;
handler_fn control_on_disable;
handler_fn control_on_estop;
handler_fn control_on_reset;
handler_fn control_on_reset_stats;
handler_fn control_on_hand_input;
handler_fn control_on_subscribe;
handler_fn control_on_debug;
handler_fn control_on_get_scene;
handler_fn control_on_list_cases;
handler_fn control_on_load_case;
handler_fn control_on_session_start;
handler_fn control_on_session_stop;
handler_fn control_on_session_status;
handler_fn control_on_session_list;
handler_fn control_on_session_show;
handler_fn control_on_session_map;
handler_fn control_on_trainee_sessions;
handler_fn control_on_guide;
handler_fn control_on_patient;
handler_fn control_on_tool;
handler_fn control_on_records_check;
handler_fn control_on_records_rebuild;
handler_fn control_on_records_backup;
handler_fn control_on_records_restore;
handler_fn control_on_login;
handler_fn control_on_accounts;
handler_fn control_on_logout;

/* The status reply of the newest published state (GetStatus, a push, a
 * guide command's answer), in control_reply.c's storage. */
void control_build_status(struct control *c, Endosim__Reply *rep);

/*
 * After the loop answered a command: waits for the state of the cycle
 * that answered, published at that cycle's end (at most a period; gives
 * up after 100 ms), so that the reply built next shows the command done.
 */
void control_await_state(struct control *c);

/*
 * A session's sedation NAME ("": [pain] sedation) to the patient, before
 * the session starts. 0 (done, or no patient and NAME ""), or -1 refused
 * (REP says why: no such level, no patient to sedate, the loop did not
 * take it).
 */
int control_sedate(struct control *c, struct client *cl, const char *name,
		   Endosim__Reply *rep);

/* Loads case NAME (IDLE only, never during a session). 0, or -1 refused
 * (REP says why). */
int control_load_case(struct control *c, struct client *cl,
		      const char *name, Endosim__Reply *rep);

#endif
