/* shot.c - see shot.h. */
#include "viewer/shot.h"

#include <errno.h>
#include <stdlib.h>

#include <epoxy/gl.h>
#include <stb_image_write.h>

int shot_write(const char *path, int w, int h)
{
	unsigned char *px = malloc((size_t)w * h * 3);
	int ok;

	if (!px) {
		return -ENOMEM;
	}
	glReadBuffer(GL_BACK);
	glPixelStorei(GL_PACK_ALIGNMENT, 1);
	glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, px);
	stbi_flip_vertically_on_write(1); /* GL's rows run bottom-up */
	ok = stbi_write_png(path, w, h, 3, px, w * 3);
	free(px);
	return ok ? 0 : -EIO;
}
