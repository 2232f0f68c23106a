/*
 * shot.h - screenshots: the framebuffer being drawn (the back buffer,
 * before the swap) written as a PNG with stb_image_write.
 *
 * Main thread, with the GL context current; allocates a frame's pixels.
 */
#ifndef ENDOVIEW_SHOT_H
#define ENDOVIEW_SHOT_H

/* Writes the W x H framebuffer to PATH. Returns 0 or a negative errno. */
int shot_write(const char *path, int w, int h);

#endif
