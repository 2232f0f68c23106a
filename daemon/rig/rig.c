/* rig.c - see rig.h. */
#include "rig/rig.h"

#include <stddef.h>

void rig_destroy(struct rig *rig)
{
	if (rig) {
		rig->ops->destroy(rig);
	}
}
