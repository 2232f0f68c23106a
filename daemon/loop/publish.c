/* publish.c - see publish.h. */
#include "loop/publish.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/log.h"

struct publish {
	struct endosim_shm *shm;
	int fd; /* held open with an exclusive flock: one writer per name */
	char name[256];
};

struct publish *publish_create(const char *name, uint32_t period_ns,
			       uint64_t start_ns)
{
	struct publish *p = calloc(1, sizeof(*p));
	int fd;

	if (!p) {
		log_err("shm %s: out of memory", name);
		return NULL;
	}
	snprintf(p->name, sizeof(p->name), "%s", name);
	fd = shm_open(name, O_CREAT | O_RDWR | O_CLOEXEC, 0644);
	if (fd < 0) {
		log_err("shm %s: cannot create: %m", name);
		goto free_p;
	}
	if (flock(fd, LOCK_EX | LOCK_NB) < 0) {
		log_err("shm %s: in use by another endosimd", name);
		close(fd);
		goto free_p;
	}
	if (fchmod(fd, 0644) < 0 ||
	    ftruncate(fd, sizeof(struct endosim_shm)) < 0) {
		log_err("shm %s: cannot size: %m", name);
		goto close_fd;
	}
	p->shm = mmap(NULL, sizeof(struct endosim_shm), PROT_READ | PROT_WRITE,
		      MAP_SHARED, fd, 0);
	if (p->shm == MAP_FAILED) {
		log_err("shm %s: cannot map: %m", name);
		goto close_fd;
	}
	p->fd = fd;
	memset(p->shm, 0, sizeof(*p->shm));
	p->shm->version = ENDOSIM_SHM_VERSION;
	p->shm->size = sizeof(struct endosim_shm);
	p->shm->writer_pid = getpid();
	p->shm->period_ns = period_ns;
	p->shm->start_ns = start_ns;
	seqlock_init(&p->shm->lock);
	/* magic last: a reader that sees it sees a complete header */
	atomic_thread_fence(memory_order_release);
	p->shm->magic = ENDOSIM_SHM_MAGIC;
	return p;

close_fd:
	close(fd);
	shm_unlink(name);
free_p:
	free(p);
	return NULL;
}

void publish_destroy(struct publish *p)
{
	if (!p) {
		return;
	}
	munmap(p->shm, sizeof(*p->shm));
	shm_unlink(p->name);
	close(p->fd);
	free(p);
}

void publish_state(struct publish *p, const struct endosim_state *state)
{
	seqlock_write_begin(&p->shm->lock);
	memcpy(&p->shm->state, state, sizeof(*state));
	seqlock_write_end(&p->shm->lock);
}

int publish_read(const struct publish *p, struct endosim_state *out)
{
	for (int tries = 0; tries < 1000; tries++) {
		uint64_t seq = seqlock_read_begin(&p->shm->lock);

		memcpy(out, &p->shm->state, sizeof(*out));
		if (!seqlock_read_retry(&p->shm->lock, seq)) {
			return 0;
		}
	}
	return -EAGAIN;
}
