/* Per-frame placement of the BOM grid and of every ray-aligned map, computed on
 * the CPU in double precision and uploaded as floats; the GPU and the C mirror
 * (cpu_mirror.c) then evaluate the same float formulas. */
#ifndef ROMA_MAP_PARAMS_H
#define ROMA_MAP_PARAMS_H

#include <stdint.h>

#include "roma_shared.h"

/* The range of world coordinates where the grid's float arithmetic stays exact
 * enough: every corner of the grid cube within +-ROMA_GRID_MAX_COORDINATE (a quarter
 * of FLT_MAX, so that differences, rotated box extents and ray distances stay
 * finite), and cells no smaller than ROMA_GRID_MIN_CELL (so that a hundredth of a
 * cell is still a normal float on GPUs that flush subnormals). */
#define ROMA_GRID_MAX_COORDINATE 8.5e37
#define ROMA_GRID_MIN_CELL 1e-35

typedef enum roma_grid_status {
    ROMA_GRID_OK = 0,
    ROMA_GRID_EMPTY,     /* no extent, or bounds not finite */
    ROMA_GRID_TOO_LARGE, /* a corner of the grid beyond ROMA_GRID_MAX_COORDINATE */
    ROMA_GRID_TOO_SMALL  /* cells smaller than ROMA_GRID_MIN_CELL */
} roma_grid_status;

/* Whether a grid can be placed around [bmin, bmax] (jitter included). */
roma_grid_status roma_grid_check(const float bmin[3], const float bmax[3], uint32_t resolution,
                                 float margin_cells);

/* Grid cube around [bmin, bmax]: side = max extent * RES / (RES - 2 margin), centred,
 * origin shifted by jitter (in cells, each in [-0.5, 0.5]). Returns 0 when
 * roma_grid_check refuses the box. */
int roma_compute_grid(const float bmin[3], const float bmax[3], uint32_t resolution,
                      uint32_t angular, float margin_cells, const float jitter_cells[3],
                      roma_grid_params *out);

/* Frame of the map for unit candidate dir: basis (t, b, dir), box = bounds of the grid
 * cube in that basis, cells = box extent / RES per axis. */
void roma_compute_map_frame(const roma_grid_params *grid, const float dir[3], roma_map_frame *out);

#endif /* ROMA_MAP_PARAMS_H */
