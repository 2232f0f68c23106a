/*
 * emu.h - what the drive emulators share: the motor a drive moves (a plant
 * at the motor shaft, turned by the drive's torque and a scripted hand),
 * the control FIFO that tells them what to break, the state file that says
 * what they see, and the hex trace.
 *
 * Control: one command per line written to the FIFO (echo "unplug X" >
 * FIFO); each emulator documents its commands. State: the file is replaced
 * atomically (write, rename) a few times a second, one line per device of
 * "key=value" words, for scripts to read with awk.
 *
 * Single-threaded use, or under the caller's lock.
 */
#ifndef ENDOSIM_EMU_H
#define ENDOSIM_EMU_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "model/plant.h"

/* The motor and what turns it, at the motor shaft (rad, N m). */
struct emu_motor {
	struct plant plant;
	double hand_nm;       /* the hand's steady torque */
	double hand_amp_nm;   /* and its sine, of this amplitude */
	double hand_hz;
	double hold_nm_per_rad; /* the hand holds the knob near 0 */
	bool moving;          /* the hand turns it at a set speed instead */
	double move_rad_s;
	double drive_nm;      /* the drive's torque, set by the emulator */
	double t_s;
};

struct emu_motor_params {
	double inertia_kg_m2;
	double viscous_nm_s;
	double coulomb_nm;
	double hold_nm_per_rad;
};

#define EMU_MOTOR_DEFAULTS                                                 \
	{ .inertia_kg_m2 = 5e-4, .viscous_nm_s = 2e-4, .coulomb_nm = 0.0, \
	  .hold_nm_per_rad = 0.0 }

void emu_motor_init(struct emu_motor *m, const struct emu_motor_params *p);

/*
 * Advances the motor by DT_S under its drive and hand torques, in 1 ms
 * steps: at most 50 ms of them, an emulator that slept longer does not
 * catch up in a burst. A motor turned at a set speed (move) is not
 * integrated and keeps the whole DT_S: a test measures its speed over
 * the daemon's clock, which a pause of the emulator does not stop.
 */
void emu_motor_advance(struct emu_motor *m, double dt_s);

/* The hand: "TORQUE [FREQ_HZ]" (a sine about 0 when FREQ is given). */
int emu_motor_hand(struct emu_motor *m, const char *args);

/* Parses "-o NAME=VALUE" motor options; true when NAME was one of them. */
bool emu_motor_option(struct emu_motor_params *p, const char *arg);

/* CLOCK_MONOTONIC, s. */
double emu_now_s(void);

/* Sleeps S seconds. */
void emu_sleep_s(double s);

/* The control FIFO: created if missing, opened non-blocking. -1 on error. */
int emu_control_open(const char *path);

/*
 * Reads what is waiting on FD and calls FN for each complete line (without
 * its newline). BUF keeps a partial line between calls.
 */
struct emu_lines {
	char buf[512];
	size_t len;
};

void emu_control_poll(int fd, struct emu_lines *lb,
		      void (*fn)(void *ctx, char *line), void *ctx);

/* Replaces PATH with TEXT atomically, soon: a thread of its own writes
 * the newest TEXT handed over, so that the caller never waits on the
 * disk. */
void emu_state_write(const char *path, const char *text);

/* Appends a trace line: time, TAG, the bytes in hex, NOTE. */
void emu_trace(FILE *f, const char *tag, const uint8_t *p, size_t n,
	       const char *note);

/* Splits LINE at blanks into at most MAX words; returns the count. */
int emu_words(char *line, char **word, int max);

#endif
