/*
 * branch.h - lockstep runs that share their beginning, with the beginning
 * played once: the caller plays the common part, then branch_run() plays
 * each remainder in a child process (fork(): a copy of the run as it
 * stands, the very state a run of its own would have reached, bit for
 * bit), one child at a time, and copies back what it measured. The runs
 * are the same as played one after another from the start; the shared
 * part costs once.
 *
 * The remainder must not fail through cmocka: a failed assertion in the
 * child would jump into the child's copy of the test runner. It records
 * what it saw; the caller asserts on it. Output the child prints comes
 * before branch_run() returns (flushed on both sides). One thread.
 * Include after cmocka.h.
 */
#ifndef ENDOSIM_BRANCH_H
#define ENDOSIM_BRANCH_H

#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

/*
 * Runs FN(ARG, OUT) in a child of this process as it stands, then copies
 * the SIZE bytes that FN left in OUT (its copy's) back into OUT here.
 * Fails the test (cmocka) when the child could not run, did not exit 0,
 * or gave back less.
 */
static inline void branch_run(void (*fn)(void *arg, void *out), void *arg,
			      void *out, size_t size)
{
	size_t got = 0;
	int fd[2], status;
	ssize_t n;
	pid_t pid;

	fflush(stdout);
	fflush(stderr);
	assert_int_equal(pipe(fd), 0);
	pid = fork();
	assert_true(pid >= 0);
	if (pid == 0) {
		close(fd[0]);
		fn(arg, out);
		fflush(stdout);
		fflush(stderr);
		for (got = 0; got < size; got += (size_t)n) {
			n = write(fd[1], (char *)out + got, size - got);
			if (n <= 0) {
				_exit(1);
			}
		}
		_exit(0);
	}
	close(fd[1]);
	while (got < size &&
	       (n = read(fd[0], (char *)out + got, size - got)) > 0) {
		got += (size_t)n;
	}
	close(fd[0]);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	assert_int_equal(got, size);
}

#endif
