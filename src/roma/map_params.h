/* Per-frame placement of the BOM grid and of every ray-aligned map, computed on
 * the CPU in double precision and uploaded as floats; the GPU and the C mirror
 * (cpu_mirror.c) then evaluate the same float formulas. */
#ifndef ROMA_MAP_PARAMS_H
#define ROMA_MAP_PARAMS_H

#include <stdint.h>

#include "roma_shared.h"

/* Grid cube around [bmin, bmax]: side = max extent * RES / (RES - 2 margin), centred,
 * origin shifted by jitter (in cells, each in [-0.5, 0.5]). Returns 0 for an empty or
 * non-finite box. */
int roma_compute_grid(const float bmin[3], const float bmax[3], uint32_t resolution,
                      uint32_t angular, float margin_cells, const float jitter_cells[3],
                      roma_grid_params *out);

/* Frame of the map for unit candidate dir: basis (t, b, dir), box = bounds of the grid
 * cube in that basis, cells = box extent / RES per axis. */
void roma_compute_map_frame(const roma_grid_params *grid, const float dir[3], roma_map_frame *out);

#endif /* ROMA_MAP_PARAMS_H */
