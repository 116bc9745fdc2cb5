/* Worst-case loop iterations of the trace functions (loop_costs.h). */
#include "trace/loop_costs.h"

#include <math.h>

#include "roma_shared.h"

/* One iteration of the loop that runs the item (a light, a sample), besides its calls. */
#define LOOP_ITSELF 1u
/* What checks a segment's end at its light: a point light's up to three walks through the BOM
 * and one through the surface grid (roma_light_end_blocked); an area light's five lookups, one
 * walk through the grid and one through the BOM (roma_emitter_end_blocked) are fewer. */
#define LIGHT_END (3u * ROMA_LIGHT_END_CELLS + ROMA_LIGHT_SURFACE_CELLS)

static uint32_t min_u32(uint64_t a, uint64_t b) { return (uint32_t)(a < b ? a : b); }

uint32_t roma_loop_cost_walk(roma_loop_grid g, float length, uint32_t max_cells)
{
    const uint64_t leave = 3ull * g.res + 1; /* an unbounded ray leaves within 3 RES + 1 cells */
    uint64_t cells = leave;
    const double cells_long = g.cell > 0.0f ? (double)length / g.cell : INFINITY;
    if (cells_long >= 0.0 && cells_long < (double)leave) /* NaN too: leave */
        cells = (uint64_t)ceil(1.7320509 * cells_long) + 4;
    return min_u32(min_u32(cells, leave), max_cells);
}

/* A query's cost in each cascade level, plus the levels' own loops (roma_level_of, the
 * exits' three axes and the walk over the levels). */
static uint32_t across_levels(roma_loop_grid g, uint64_t per_level)
{
    const uint64_t levels = g.levels > 1 ? g.levels : 1;
    return min_u32(levels * per_level + (levels > 1 ? 5 * levels : 0), UINT32_MAX);
}

uint32_t roma_loop_cost_snapped(roma_loop_grid g) { return across_levels(g, g.res / 32u); }

uint32_t roma_loop_cost_unsnapped(roma_loop_grid g, uint32_t max_steps)
{
    const uint64_t steps = min_u32(max_steps, 2ull * g.res);
    return across_levels(g, steps * (g.res / 32u + 1u));
}

uint32_t roma_loop_cost_shadow_ray(const roma_shadow_cost *s)
{
    if (s->exact)
        return roma_loop_cost_walk(s->grid, INFINITY, UINT32_MAX);
    const uint64_t start = roma_loop_cost_walk(s->grid, s->start_walk * s->tmin, 64);
    const uint64_t query = roma_loop_cost_unsnapped(s->grid, s->max_steps);
    /* The walk back's reach: back_skip cells up to RES 128, as far in metres above
     * (roma_back_skip_cells). */
    const uint64_t reach = (uint64_t)s->back_skip * (s->grid.res > 128 ? s->grid.res / 128 : 1);
    const uint64_t back = reach + query, sun = roma_loop_cost_snapped(s->grid);
    return min_u32(start + query + (back > sun ? back : sun), UINT32_MAX);
}

uint32_t roma_loop_cost_area_sample(const roma_shadow_cost *s, uint32_t emitters)
{
    uint32_t search = 1; /* while (lo < hi) halves [0, emitters): ceil(log2) iterations, one more at most */
    while (emitters > 1u && (1ull << (search - 1)) < emitters)
        ++search;
    roma_shadow_cost area = *s;
    area.back_skip = ROMA_BACK_SKIP_AREA;
    return min_u32((uint64_t)LOOP_ITSELF + search + roma_loop_cost_shadow_ray(&area) + LIGHT_END, UINT32_MAX);
}

uint32_t roma_loop_cost_punctual_light(const roma_shadow_cost *s)
{
    roma_shadow_cost point = *s;
    point.back_skip = ROMA_BACK_SKIP_POINT;
    /* A directional light at a GI hit: its start walk (64 cells, or to the edge when exact)
     * and one snapped query, within the shadow ray's bound. */
    return min_u32((uint64_t)LOOP_ITSELF + roma_loop_cost_shadow_ray(&point) + LIGHT_END, UINT32_MAX);
}

uint32_t roma_loop_cost_ao_ray(roma_loop_grid g, float skip, float radius, uint32_t surface_cells, uint32_t ray_cells)
{
    const float start = skip < radius ? skip : radius;
    /* The surface grid's check: its walk and the two cascade levels it looks up. */
    const uint64_t surfaces = surface_cells ? surface_cells + 2u * (g.levels > 1 ? g.levels - 1 : 0u) : 0u;
    /* The ray's walk through the grid (each step, a cell's or an empty (super-)block's, to a
     * cell farther along the ray; two a cell stated, against the jumps' rounding) and the
     * un-snapped queries over its runs of crowded cells: at most one run in two cells, each
     * query up to two texels per trace cell of its run grown by a cell on both sides (grid
     * cells up to 1.5 trace cells), and four. */
    const uint64_t runs = ray_cells / 2u + 1u, steps = 3ull * ray_cells + 8u * runs;
    const uint64_t ray = ray_cells ? 2ull * ray_cells + (uint64_t)across_levels(g, steps * (g.res / 32u + 1u)) +
                                         runs * (g.levels > 1 ? 5u * g.levels : 0u)
                                   : 0u;
    return min_u32(LOOP_ITSELF + roma_loop_cost_walk(g, start, 64) + surfaces + roma_loop_cost_snapped(g) + ray,
                   UINT32_MAX);
}

uint32_t roma_loop_cost_gi_bounce(roma_loop_grid g, float skip, int exact)
{
    const uint32_t start = exact ? roma_loop_cost_walk(g, INFINITY, UINT32_MAX) : roma_loop_cost_walk(g, skip, 64);
    const uint32_t surface = 5u + 6u;                              /* along the hit's column, then around it */
    const uint32_t point = roma_loop_cost_walk(g, 64.0f * g.cell, 128); /* the hit's point checked */
    return LOOP_ITSELF + start + roma_loop_cost_snapped(g) + surface + point;
}
