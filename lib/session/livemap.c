/* livemap.c - see livemap.h. */
#include "session/livemap.h"

#include <math.h>

/* The ramp's ends, unseen then seen, 0..255 a channel: on the screen
 * 0.93, 0.16, 0.20 and 0.20, 0.62, 0.32 of full scale. */
static const double ramp[][2][3] = {
	[LIVEMAP_ON_PAGE] = { { 214, 60, 60 }, { 154, 230, 180 } },
	[LIVEMAP_ON_SCREEN] = { { 237.15, 40.8, 51 }, { 51, 158.1, 81.6 } },
};

void livemap_quantise(const struct metrics_map *map,
		      uint8_t cells[LIVEMAP_CELLS])
{
	for (int i = 0; i < METRICS_MAP_S; i++) {
		for (int k = 0; k < METRICS_MAP_A; k++) {
			double v = map->seen[i][k];
			uint8_t *c = &cells[i * METRICS_MAP_A + k];

			if (!(v >= 0)) {
				*c = LIVEMAP_NO_WALL;
				continue;
			}
			*c = (uint8_t)lround(fmin(v, 1.0) * LIVEMAP_FULL);
		}
	}
}

double livemap_share(uint8_t cell)
{
	return cell == LIVEMAP_NO_WALL ? -1 : (double)cell / LIVEMAP_FULL;
}

double livemap_mean_seen(const uint8_t *cells, size_t n)
{
	double sum = 0;
	size_t walls = 0;

	for (size_t i = 0; i < n; i++) {
		if (cells[i] != LIVEMAP_NO_WALL) {
			sum += livemap_share(cells[i]);
			walls++;
		}
	}
	return walls ? sum / (double)walls : 0;
}

void livemap_colour(enum livemap_background bg, double share,
		    double rgb[3])
{
	const double *unseen = ramp[bg][0], *seen = ramp[bg][1];

	for (int c = 0; c < 3; c++) {
		rgb[c] = unseen[c] + share * (seen[c] - unseen[c]);
	}
}
