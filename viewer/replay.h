/*
 * replay.h - endoview --replay: a recorded session (docs/SESSION_FORMAT.md,
 * proto/session_file.h) played back without the daemon.
 *
 * replay_open() reads the file and rebuilds the colon it was recorded on
 * with the daemon's own code: the CASE frame parsed as a case file
 * (anatomy_parse()), built at the HEADER's resolution (step_m,
 * ring_vertices, segment_m) with the CONFIG frame's contact radius
 * (colon_create()), and served as GetScene would serve it (scene.h), so
 * the viewer's model, levels of detail and views are made exactly as in
 * live mode. The scope's parameters (bending length, wheel gains and
 * limits) come from CONFIG too; a CONFIG this viewer cannot read leaves
 * the defaults (logged).
 *
 * The clock: the replay's time t (s) counts from the first record's stamp
 * to the last's (the duration); it runs at a speed (x0.25 .. x8) unless
 * paused, and stops at the end. The state shown at t is the last record
 * at or before it (session_file_seek()), as session_record_to_state()
 * gives it, with the scope's tube rebuilt: the records keep the insertion,
 * roll and wheels and each mobile span's bow, not the tube, so the tube
 * is scope_update() on the colon's centreline bowed as the record before
 * says (the force loop makes its pose before the haptics bow the colon,
 * and publishes the bows after: a cycle's tube is on last cycle's bows).
 * In the rod model (the record's rod.model) the state's rod is the SHAPE
 * frame at or before the record (session_shape_to_state(): the rod's
 * points, roll and the colon's nodes, and each span's bow_m, its loop's
 * size, from them), and the tube is the inserted depth of the SHAPE's
 * record along the rod's points (live, it is the rod's before the step
 * that made the points: a cycle's motion apart); no colon is bowed.
 *
 * What the tools left (lib/model/tool.h), which a record does not hold
 * whole, from the records up to the one shown (docs/SESSION_FORMAT.md):
 * each polyp held (tool_captured), cut, retrieved, bleeding, clipped or
 * stopped by the tool_events of its records; the points bleeding, their
 * flow each (the stalk's, with the file's [tool]) and the strongest
 * one's place, its polyp's base as tool_place_polyps() puts it on the
 * rebuilt colon; the clips placed and the last one's place, its jaws'
 * point on the pose of the record that placed it (tool_pose() of the
 * recorded tip and tool depth); each cut polyp's place, the last that a
 * record's tool_lying_polyp gave for it at or before (the place where it
 * was cut before any does). replay_open() indexes the records with
 * events and each polyp's changes of place once; a state shown folds
 * the events up to it (a few hundred) and finds each place by bisection.
 *
 * Main thread only. replay_open() allocates (the file, the colon: ~0.1 s
 * at the default resolution); the rest does not.
 */
#ifndef ENDOVIEW_REPLAY_H
#define ENDOVIEW_REPLAY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "proto/client.h"
#include "proto/endosim_shm.h"

#define REPLAY_SCENE_ID 1
#define REPLAY_SPEED_MIN 0.25
#define REPLAY_SPEED_MAX 8.0

struct replay;

/*
 * Opens the session file PATH. NULL with one line in ERR: the file cannot
 * be read, is not a session file, has a format this viewer does not know,
 * holds no record, or its case does not build.
 */
struct replay *replay_open(const char *path, char *err, size_t errsize);

/* NULL is fine. */
void replay_destroy(struct replay *r);

/* The colon as GetScene would serve it (id REPLAY_SCENE_ID); valid while
 * R lives, not for client_scene_free(). */
const struct client_scene *replay_scene(struct replay *r);

/* The header's trainee and case ("" when absent). */
const char *replay_trainee(const struct replay *r);
const char *replay_case(const struct replay *r);

/* The records read, and how many bytes were cut or damaged after them. */
size_t replay_records(const struct replay *r);
size_t replay_bytes_ignored(const struct replay *r);

/* The bow (m) beyond which the session's metrics count a loop
 * (sessioninputs_file_metrics_params()). */
double replay_loop_threshold_m(const struct replay *r);

/* The pressure gauge's marks: the session's [patient] relief_pa (0:
 * none) and wall_strength_n_per_m, as recorded (the defaults where not). */
void replay_patient_limits(const struct replay *r, double *relief_pa,
			   double *strength_n_per_m);

/* Seconds from the first record to the last. */
double replay_duration(const struct replay *r);

/* The clock's time (s), 0 .. duration. */
double replay_time(const struct replay *r);

/* Moves the clock to T_S (clamped to 0 .. duration). */
void replay_seek(struct replay *r, double t_s);

/* Runs the clock on by DT_S of real time times the speed, unless paused. */
void replay_advance(struct replay *r, double dt_s);

void replay_set_paused(struct replay *r, bool paused);
bool replay_paused(const struct replay *r);

/* Sets the speed, clamped to REPLAY_SPEED_MIN .. REPLAY_SPEED_MAX. */
void replay_set_speed(struct replay *r, double speed);
double replay_speed(const struct replay *r);

/* The state at the clock's time, the tube rebuilt (see above); valid
 * until the next call. */
const struct endosim_state *replay_state(struct replay *r);

/* The record at T_S as a state, without the tube (zeroed): cheap, for the
 * strip chart. */
void replay_record_at(const struct replay *r, double t_s,
		      struct endosim_state *out);

#endif
