/*
 * fields.h - one description of the haptic parts the force loop publishes
 * (struct endosim_haptics_state) as the wire carries them (HapticsStatus):
 * each one's name (its JSON key in `endoctl --json status`, its unit as a
 * suffix), kind, place in the shared-memory state and in the protobuf
 * message. The control thread's copy into the reply and endoctl's JSON
 * are made of it: a part added to the published haptics is added to both
 * structs, to endosim.proto and to this table (fields.c), in JSON order.
 */
#ifndef ENDOSIM_FIELDS_H
#define ENDOSIM_FIELDS_H

#include <stddef.h>

#include "endosim.pb-c.h"
#include "endosim_shm.h"

enum fields_kind {
	FIELDS_DOUBLE,   /* double in both */
	FIELDS_BOOL,     /* uint32_t 0/1 in the state, a bool on the wire */
	FIELDS_UINT,     /* uint32_t in both */
	FIELDS_VECTOR,   /* double[n] in the state, repeated double */
};

struct fields_field {
	const char *name;
	enum fields_kind kind;
	size_t n;        /* FIELDS_VECTOR: its length */
	size_t shm;      /* offset into struct endosim_haptics_state */
	size_t pb;       /* offset into Endosim__HapticsStatus (the array's
			    pointer for a vector) */
	size_t pb_n;     /* FIELDS_VECTOR: offset of its n_ count */
};

extern const struct fields_field fields_haptics[];
extern const size_t fields_n_haptics;

/*
 * Fills P (initialised here) from H; P's repeated fields point into H,
 * which must outlive it. Any thread; never allocates.
 */
void fields_haptics_to_pb(Endosim__HapticsStatus *p,
			  struct endosim_haptics_state *h);

#endif
