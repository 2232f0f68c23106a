/*
 * notify_listen - a stand-in for systemd's notify socket (NOTIFY_SOCKET):
 * binds a datagram socket at PATH and prints each message it receives as
 * one line "SECONDS MESSAGE", SECONDS on CLOCK_MONOTONIC, newlines in the
 * message turned into spaces. Runs until killed.
 *
 *   notify_listen PATH
 */
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>
#include "proto/endosim_shm.h"

int main(int argc, char **argv)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	char msg[4096];
	struct timespec ts;
	ssize_t n;
	int fd;

	if (argc != 2 || strlen(argv[1]) >= sizeof(addr.sun_path)) {
		fprintf(stderr, "usage: notify_listen PATH\n");
		return 2;
	}
	strcpy(addr.sun_path, argv[1]);
	unlink(argv[1]);
	fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
	if (fd < 0 || bind(fd, (struct sockaddr *)&addr, sizeof(addr)) < 0) {
		perror("notify_listen");
		return 1;
	}
	while ((n = recv(fd, msg, sizeof(msg) - 1, 0)) >= 0) {
		msg[n] = '\0';
		for (ssize_t i = 0; i < n; i++) {
			msg[i] = msg[i] == '\n' ? ' ' : msg[i];
		}
		clock_gettime(CLOCK_MONOTONIC, &ts);
		printf("%.6f %s\n", (double)ts.tv_sec +
		       (double)ts.tv_nsec / ENDOSIM_NS_PER_S, msg);
		fflush(stdout);
	}
	perror("notify_listen: recv");
	return 1;
}
