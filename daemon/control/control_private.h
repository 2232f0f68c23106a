/*
 * control_private.h - what the parts of the control thread share
 * (control.c: sockets, clients, dispatch, the thread; control_reply.c:
 * status, stats, configuration, commands, the hand, subscriptions and test
 * commands; control_case.c: the scene and the cases; control_session.c:
 * training sessions; control_trainee.c: a trainee's sessions through the
 * session directory's index). Control thread only, as all of control.h's
 * work.
 */
#ifndef ENDOSIM_CONTROL_PRIVATE_H
#define ENDOSIM_CONTROL_PRIVATE_H

#include <errno.h>
#include <grp.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "control/control.h"
#include "proto/client.h"
#include "proto/frame.h"
#include "proto/names.h"
#include "proto/version.h"
#include "conf/cases.h"
#include "loop/faults.h"
#include "proto/fields.h"
#include "rig/guide.h"
#include "loop/inject.h"
#include "base/log.h"
#include "base/mono.h"
#include "model/scene.h"
#include "session/sessiondir.h"
#include "session/sessionindex.h"
#include "session/sessionpb.h"

#define MAX_EVENTS 32
#define MAX_PEER_GROUPS 256
#define COMMAND_TIMEOUT_MS 200
#define MAX_PUSH_HZ 1000.0
#define MAX_HOLD_S 10.0
#define SWAP_TIMEOUT_MS 500

enum { TAG_WAKE = 0, TAG_RO = 1, TAG_RW = 2, TAG_CLIENT = 3 };

struct client {
	int fd;               /* -1: free slot */
	bool rw;              /* connected to the read-write socket */
	bool may_command;     /* rw, and root or in the command group */
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

/* Storage for the reply being built: no allocation per reply. */
struct reply_buf {
	Endosim__StatusReply status;
	Endosim__AxisStatus axes[ENDOSIM_AXES];
	Endosim__AxisStatus *axes_p[ENDOSIM_AXES];
	Endosim__Fault faults[ENDOSIM_FAULT_BITS];
	Endosim__Fault *faults_p[ENDOSIM_FAULT_BITS];
	char fault_lines[ENDOSIM_FAULT_BITS][640];
	Endosim__StatsReply stats;
	Endosim__Histogram latency, compute;
	Endosim__BusStats buses[ENDOSIM_AXES];
	Endosim__BusStats *buses_p[ENDOSIM_AXES];
	Endosim__Histogram bus_histo[ENDOSIM_AXES][2];
	Endosim__ConfigReply config;
	Endosim__ConfigEntry *entries;
	Endosim__ConfigEntry **entries_p;
	char (*values)[CONFIG_STR + 32];
	char error[256];
	Endosim__ScopeStatus scope;
	Endosim__HapticsStatus haptics;
	Endosim__RodStatus rod;
	Endosim__GuideStatus guide;
	struct endosim_state state; /* what the status reply points into */
	Endosim__CaseListReply case_list;
	Endosim__CaseEntry *case_entries;
	Endosim__CaseEntry **case_entries_p;
	struct cases_entry *cases;
	char case_error[512];
	Endosim__SessionReply session_reply;
	Endosim__SessionInfo session;
	struct recorder_info rinfo;        /* what session points into */
	struct sessionpb_metrics metrics;
	Endosim__SessionListReply session_list;
	Endosim__SessionInfo *list_infos;
	Endosim__SessionInfo **list_infos_p;
	struct sessiondir_entry *list_entries;
	struct sessiondir_entry shown;     /* SessionShow's file */
	Endosim__MapReply map;             /* SessionMap's */
	Endosim__MapRegion map_regions[COLON_MAX_REGIONS];
	Endosim__MapRegion *map_regions_p[COLON_MAX_REGIONS];
	Endosim__MapPolyp map_found[ANATOMY_MAX_POLYPS];
	Endosim__MapPolyp *map_found_p[ANATOMY_MAX_POLYPS];
	struct recorder_map rmap;          /* what map points into */
	Endosim__TraineeReply trainee;     /* TraineeSessions': */
	Endosim__SessionInfo *trainee_infos;
	Endosim__SessionInfo **trainee_infos_p;
	struct sessionpb_scalars *trainee_metrics;
	char (*trainee_paths)[CONFIG_STR + 32];
	struct sessionindex_entry *trainee_entries;
};

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
	struct reply_buf rb;
	struct colon *colon;     /* the loop's now: read its mesh only */
	char case_path[2 * CONFIG_STR + 8]; /* the file it was built from */
	uint64_t scene_id;
	struct scene *scene;     /* GetScene's replies, made on demand */
	uint64_t rate_t0_ns, rate_cycle0;
	double loop_hz;
	pthread_t thread;
	bool running;
	_Atomic bool alive;
	_Atomic bool stop;
	bool end;                /* a test command: the thread ends */
	struct guide_path *guide_path;  /* the loop's (loop_guide()) */
	struct guide_path *guide_limbo; /* handed over, never answered:
					   freed at the end */
};

typedef void handler_fn(struct control *c, struct client *cl,
			const Endosim__Request *req, Endosim__Reply *rep);

/* Answers REP with STATUS and WHY (a constant string). */
static inline void refuse(Endosim__Reply *rep, Endosim__Status status,
			  const char *why)
{
	rep->status = status;
	rep->error = (char *)why;
}

/*
 * The requests, by job: status, stats, configuration, commands, the hand
 * and subscriptions, test commands (control_reply.c); the scene and the
 * cases (control_case.c); training sessions and their live map
 * (control_session.c).
 */
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
handler_fn control_on_debug;
handler_fn control_on_guide;

/* The status reply of the newest published state (GetStatus, a push). */
void control_build_status(struct control *c, Endosim__Reply *rep);

/* Frees the case list (the session list) the last reply was made of. */
void control_free_case_list(struct reply_buf *rb);
void control_free_session_list(struct reply_buf *rb);
void control_free_trainee(struct reply_buf *rb);

/* Loads case NAME (IDLE only, never during a session). 0, or -1 refused. */
int control_load_case(struct control *c, struct client *cl,
		      const char *name, Endosim__Reply *rep);

#endif
