/* fields.c - see fields.h. */
#include "fields.h"

#include <string.h>

#define SHM(f) offsetof(struct endosim_haptics_state, f)
#define PB(f) offsetof(Endosim__HapticsStatus, f)
#define D(f) { #f, FIELDS_DOUBLE, 0, SHM(f), PB(f), 0 }
#define V(f, n) { #f, FIELDS_VECTOR, n, SHM(f), PB(f), PB(n_##f) }

const struct fields_field fields_haptics[] = {
	{ "contact", FIELDS_BOOL, 0, SHM(contact), PB(contact), 0 },
	{ "constraints", FIELDS_UINT, 0, SHM(constraints), PB(constraints), 0 },
	V(proxy, 3),
	V(normal, 3),
	V(f_static, 3),
	D(penetration_m),
	D(curvature_rad),
	D(trans_contact_n),
	D(trans_friction_n),
	D(trans_loop_n),
	V(wheel_contact_nm, 2),
	V(wheel_tension_nm, 2),
	V(wheel_elastic_nm, 2),
	V(wire_dl_m, 2),
	D(tube_contact_nm),
	D(tube_friction_nm),
	V(damping, ENDOSIM_AXES),
	D(passivity_energy_j),
	D(passivity_damping),
};

const size_t fields_n_haptics = sizeof(fields_haptics) /
				sizeof(fields_haptics[0]);

static void field_to_pb(const struct fields_field *d,
			Endosim__HapticsStatus *p,
			struct endosim_haptics_state *h)
{
	unsigned char *src = (unsigned char *)h + d->shm;
	unsigned char *dst = (unsigned char *)p + d->pb;
	protobuf_c_boolean b;
	uint32_t u;

	switch (d->kind) {
	case FIELDS_DOUBLE:
		memcpy(dst, src, sizeof(double));
		break;
	case FIELDS_UINT:
		memcpy(dst, src, sizeof(uint32_t));
		break;
	case FIELDS_BOOL:
		memcpy(&u, src, sizeof(u));
		b = (protobuf_c_boolean)u;
		memcpy(dst, &b, sizeof(b));
		break;
	case FIELDS_VECTOR:
		memcpy(dst, &src, sizeof(double *));
		memcpy((unsigned char *)p + d->pb_n, &d->n, sizeof(size_t));
		break;
	}
}

void fields_haptics_to_pb(Endosim__HapticsStatus *p,
			  struct endosim_haptics_state *h)
{
	endosim__haptics_status__init(p);
	for (size_t i = 0; i < fields_n_haptics; i++) {
		field_to_pb(&fields_haptics[i], p, h);
	}
}
