/*
 * mono.h - the one clock of the daemon's time stamps: CLOCK_MONOTONIC in
 * nanoseconds, the clock of every *_ns field in the published state and
 * the session files. Any thread, the force loop included: no allocation,
 * no lock, never blocks.
 */
#ifndef ENDOSIM_MONO_H
#define ENDOSIM_MONO_H

#include <stdint.h>

/* CLOCK_MONOTONIC now, ns. */
uint64_t mono_ns(void);

#endif
