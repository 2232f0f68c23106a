/* shm_reader.c - see shm_reader.h. */
#include "proto/shm_reader.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

struct shm_reader {
	const struct endosim_shm *map;
	size_t size;
};

static int check_header(const struct endosim_shm *m, size_t mapped)
{
	if (mapped < sizeof(*m) || m->magic != ENDOSIM_SHM_MAGIC ||
	    m->version != ENDOSIM_SHM_VERSION || m->size != sizeof(*m)) {
		return -EPROTO;
	}
	return 0;
}

struct shm_reader *shm_reader_open(const char *name)
{
	struct shm_reader *r;
	struct stat st;
	void *map;
	int fd, err;

	fd = shm_open(name, O_RDONLY, 0);
	if (fd < 0) {
		return NULL;
	}
	if (fstat(fd, &st) < 0) {
		goto close_fd;
	}
	if ((size_t)st.st_size < sizeof(struct endosim_shm)) {
		errno = EPROTO;
		goto close_fd;
	}
	map = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_SHARED, fd, 0);
	if (map == MAP_FAILED) {
		goto close_fd;
	}
	close(fd);
	err = check_header(map, (size_t)st.st_size);
	if (err) {
		munmap(map, (size_t)st.st_size);
		errno = -err;
		return NULL;
	}
	r = calloc(1, sizeof(*r));
	if (!r) {
		munmap(map, (size_t)st.st_size);
		return NULL;
	}
	r->map = map;
	r->size = (size_t)st.st_size;
	return r;

close_fd:
	err = errno;
	close(fd);
	errno = err;
	return NULL;
}

void shm_reader_close(struct shm_reader *r)
{
	if (!r) {
		return;
	}
	munmap((void *)r->map, r->size);
	free(r);
}

int shm_reader_read(struct shm_reader *r, struct endosim_state *out,
		    unsigned int tries)
{
	uint64_t seq;

	do {
		seq = seqlock_read_begin(&r->map->lock);
		memcpy(out, &r->map->state, sizeof(*out));
		if (!seqlock_read_retry(&r->map->lock, seq)) {
			return 0;
		}
	} while (tries-- > 1);
	return -EAGAIN;
}

const struct endosim_shm *shm_reader_header(const struct shm_reader *r)
{
	return r->map;
}

bool shm_reader_writer_alive(const struct shm_reader *r)
{
	return kill(r->map->writer_pid, 0) == 0 || errno == EPERM;
}
