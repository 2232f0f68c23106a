/* livemap.c - see livemap.h. */
#include "session/livemap.h"

#include <math.h>

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
