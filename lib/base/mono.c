#include "base/mono.h"
#include "proto/endosim_shm.h"

#include <time.h>

uint64_t mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * ENDOSIM_NS_PER_S + (uint64_t)ts.tv_nsec;
}
