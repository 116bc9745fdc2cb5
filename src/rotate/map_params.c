#include "rotate/map_params.h"

#include <math.h>
#include <string.h>

#include "roma/sampling.h"

/* Side of the grid cube around [bmin, bmax], or 0 when the box is empty or not finite. */
static double grid_side(const float bmin[3], const float bmax[3], uint32_t res, float margin_cells)
{
    double extent = 0.0;
    for (int i = 0; i < 3; ++i) {
        double e = (double)bmax[i] - (double)bmin[i];
        if (!isfinite(e) || e < 0.0)
            return 0.0;
        extent = e > extent ? e : extent;
    }
    if (!(extent > 0.0) || res < 32 || margin_cells < 0.0f || 2.0 * margin_cells >= res)
        return 0.0;
    return extent * (double)res / ((double)res - 2.0 * margin_cells);
}

roma_grid_status roma_grid_check(const float bmin[3], const float bmax[3], uint32_t res, float margin_cells)
{
    double side = grid_side(bmin, bmax, res, margin_cells);
    if (!(side > 0.0))
        return ROMA_GRID_EMPTY;
    if (side / (double)res < ROMA_GRID_MIN_CELL)
        return ROMA_GRID_TOO_SMALL;
    double reach = side * (0.5 + 1.0 / (double)res); /* half the cube plus the jitter */
    for (int i = 0; i < 3; ++i) {
        double centre = 0.5 * ((double)bmin[i] + (double)bmax[i]);
        if (fabs(centre) + reach > ROMA_GRID_MAX_COORDINATE)
            return ROMA_GRID_TOO_LARGE;
    }
    return ROMA_GRID_OK;
}

int roma_compute_grid(const float bmin[3], const float bmax[3], uint32_t res, uint32_t angular,
                      float margin_cells, const float jitter[3], roma_grid_params *out)
{
    memset(out, 0, sizeof *out);
    if (roma_grid_check(bmin, bmax, res, margin_cells) != ROMA_GRID_OK)
        return 0;
    double side = grid_side(bmin, bmax, res, margin_cells);
    double cell = side / (double)res;
    for (int i = 0; i < 3; ++i) {
        double centre = 0.5 * ((double)bmin[i] + (double)bmax[i]);
        out->origin[i] = (float)(centre - 0.5 * side + (jitter ? jitter[i] : 0.0f) * cell);
    }
    out->origin[3] = (float)cell;
    out->inv_cell[0] = (float)(1.0 / cell);
    /* The smallest power of two at or above 1 / cell, and its inverse: map frames are stored
     * in grid units (world / cell, to a power of two) so that the un-snapped walk's terms have
     * the same magnitudes at every scene scale (in world units they fell below FLT_MIN in
     * scenes 1e37 wide, which a GPU flushes and the C mirror does not). */
    int e;
    frexp(cell, &e);
    out->inv_cell[1] = (float)ldexp(1.0, 1 - e);
    out->inv_cell[2] = (float)ldexp(1.0, e - 1);
    out->dims[0] = res;
    out->dims[1] = res / 32u;
    out->dims[2] = angular;
    out->dims[3] = angular * angular;
    out->level[1] = 1; /* one level, the first: map.c places a cascade's */
    return 1;
}

void roma_compute_map_frame(const roma_grid_params *grid, const float dir_in[3], roma_map_frame *out)
{
    memset(out, 0, sizeof *out);
    float t[3], b[3];
    roma_basis(dir_in, t, b);
    const double res = (double)grid->dims[0];
    const double cell = (double)grid->origin[3], side = cell * res;
    double axes[3][3];
    for (int i = 0; i < 3; ++i) {
        axes[0][i] = t[i];
        axes[1][i] = b[i];
        axes[2][i] = dir_in[i];
    }
    /* Everything relative to the grid origin: the map box of the grid cube. */
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
        for (int c = 0; c < 8; ++c) {
            double p = 0.0;
            for (int i = 0; i < 3; ++i)
                p += axes[a][i] * (((c >> i) & 1) * side);
            lo[a] = p < lo[a] ? p : lo[a];
            hi[a] = p > hi[a] ? p : hi[a];
        }
    }
    const double inv_bom_cell = 1.0 / cell;
    double corner[3] = {0.0, 0.0, 0.0}; /* the map box's (0,0,0) corner, relative to the grid origin */
    float *to_map[3] = {out->to_map_0, out->to_map_1, out->to_map_2};
    float *to_bom[4] = {out->map_to_bom_0, out->map_to_bom_1, out->map_to_bom_2, out->map_to_bom_3};
    for (int a = 0; a < 3; ++a) {
        double c = (hi[a] - lo[a]) / res;
        out->cell[a] = (float)c;
        for (int i = 0; i < 3; ++i) {
            to_map[a][i] = (float)(axes[a][i] / (c * (double)grid->inv_cell[1]));
            to_bom[a][i] = (float)(axes[a][i] * c * inv_bom_cell);
            corner[i] += axes[a][i] * lo[a];
        }
        to_map[a][3] = (float)(-lo[a] / c);
    }
    for (int i = 0; i < 3; ++i)
        to_bom[3][i] = (float)(corner[i] * inv_bom_cell);
    out->dir[0] = dir_in[0];
    out->dir[1] = dir_in[1];
    out->dir[2] = dir_in[2];
    out->dir[3] = out->cell[2];
    out->cell[3] = (float)(1.0 / ((hi[2] - lo[2]) / res)); /* cells per world unit along dir */
}
