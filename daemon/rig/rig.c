/* rig.c - see rig.h. */
#include "rig.h"

#include <stddef.h>

struct rig *rig_create(const struct config *cfg, struct hand *hand)
{
	switch (cfg->rig.backend) {
	case CONFIG_BACKEND_SIM:
		return rig_sim_create(cfg, hand);
	case CONFIG_BACKEND_DRIVES:
		return rig_drives_create(cfg, hand);
	}
	return NULL;
}

void rig_destroy(struct rig *rig)
{
	if (rig) {
		rig->ops->destroy(rig);
	}
}
