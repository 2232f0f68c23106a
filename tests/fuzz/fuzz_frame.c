/*
 * fuzz_frame - libFuzzer target: a byte stream as a client would send it to
 * endosimd's sockets, through the framing (read in chunks whose size the
 * input chooses) and the request decoder, then the checks the control
 * thread applies to a decoded request (version, body, SetParam through the
 * configuration table, HandInput's forces).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "conf/config.h"
#include "proto/endosim.pb-c.h"
#include "proto/frame.h"

static void check_request(const Endosim__Request *req)
{
	static struct config cfg;
	char err[256];

	if (req->body_case == ENDOSIM__REQUEST__BODY_SET_PARAM &&
	    req->set_param->key && req->set_param->value) {
		config_defaults(&cfg);
		config_set(&cfg, req->set_param->key, req->set_param->value,
			   true, err, sizeof(err));
	}
	if (req->body_case == ENDOSIM__REQUEST__BODY_GET_CONFIG &&
	    req->get_config->key) {
		(void)config_key_find(req->get_config->key);
	}
	if (req->body_case == ENDOSIM__REQUEST__BODY_HAND_INPUT) {
		for (size_t i = 0; i < req->hand_input->n_force; i++) {
			(void)isfinite(req->hand_input->force[i]);
		}
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct frame_rx rx;
	size_t chunk, room, len;
	const uint8_t *msg;

	if (size < 1 || frame_rx_init(&rx, 4096)) {
		return 0;
	}
	chunk = (size_t)data[0] % 64 + 1;
	data++;
	size--;
	while (size) {
		size_t n = size < chunk ? size : chunk;
		uint8_t *dst = frame_rx_space(&rx, &room);

		n = n < room ? n : room;
		memcpy(dst, data, n);
		frame_rx_commit(&rx, n);
		data += n;
		size -= n;
		int r;

		while ((r = frame_rx_next(&rx, &msg, &len)) == 1) {
			Endosim__Request *req =
				endosim__request__unpack(NULL, len, msg);

			if (req) {
				check_request(req);
				endosim__request__free_unpacked(req, NULL);
			}
		}
		if (r < 0) {
			break; /* the daemon closes the connection here */
		}
	}
	frame_rx_free(&rx);
	return 0;
}
