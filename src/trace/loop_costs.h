/* Worst-case loop iterations, per shader lane, of the GLSL functions libroma's passes loop
 * over (include/roma/trace.glsl and ray_start.glsl, shaders/include/roma_lights.glsl and
 * roma_gi_bounce.glsl), from each loop's own trip count, for splitting a pass's work across
 * dispatches on devices with a loop budget (src/vulkan/loop_budget.h). A bound per lane
 * bounds a SIMD vector's count too: the vector runs a loop as long as its longest lane. The
 * loop guard (src/vulkan/loop_guard.h) checks them on the tests' scenes. */
#ifndef ROMA_TRACE_LOOP_COSTS_H
#define ROMA_TRACE_LOOP_COSTS_H

#include <stdint.h>

/* The grid the trace functions walk: RES, a BOM cell's world size (the finest level's) and
 * the map's cascade levels (0 or 1: one), each of which a query may walk in turn. */
typedef struct roma_loop_grid {
    uint32_t res;
    float cell;
    uint32_t levels;
} roma_loop_grid;

/* roma_bom_walk over `length` world units (infinite: to the grid's edge), at most max_cells
 * cells: one iteration per cell it crosses, which is at most sqrt(3) per cell of length plus
 * 4, and 3 RES + 1 before it leaves the grid. */
uint32_t roma_loop_cost_walk(roma_loop_grid g, float length, uint32_t max_cells);
/* roma_trace_snapped: one column's words, RES / 32, in each level (and the levels' own loops). */
uint32_t roma_loop_cost_snapped(roma_loop_grid g);
/* roma_trace_unsnapped: max_steps texels, at most 2 RES before the ray leaves the map, each
 * reading up to RES / 32 words, in each level. */
uint32_t roma_loop_cost_unsnapped(roma_loop_grid g, uint32_t max_steps);

/* A shadow ray of roma_ray_visible (roma_lights.glsl): its start walked over start_walk x
 * tmin, the un-snapped query, the walk back from the light over at most back_skip cells and
 * the second query (or the snapped one of a ray without an end); exact (the study's voxel
 * baseline): one walk to the grid's edge. */
typedef struct roma_shadow_cost {
    roma_loop_grid grid;
    float tmin, start_walk;
    uint32_t max_steps, back_skip;
    int exact;
} roma_shadow_cost;
uint32_t roma_loop_cost_shadow_ray(const roma_shadow_cost *s);
/* One area-light sample (roma_area_sample_irradiance): the emitter's binary search over
 * `emitters`, its shadow ray (back skip ROMA_BACK_SKIP_AREA) and the walks at its light's end. */
uint32_t roma_loop_cost_area_sample(const roma_shadow_cost *s, uint32_t emitters);
/* One punctual light of roma_punctual_irradiance (back skip ROMA_BACK_SKIP_POINT, the walks
 * at its end), a directional one included, plus the loop over the lights. */
uint32_t roma_loop_cost_punctual_light(const roma_shadow_cost *s);
/* One AO ray: its start walked over min(skip, radius) (with surface_cells > 0, then through at
 * most that many cells of the surface grid: ao_images_surfaces.comp), then one snapped query;
 * with ray_cells > 0, the ray's walk through at most that many cells of the grid and the
 * un-snapped queries over its runs of crowded cells (ao_images_surface_rays.comp). */
uint32_t roma_loop_cost_ao_ray(roma_loop_grid g, float skip, float radius, uint32_t surface_cells,
                               uint32_t ray_cells);
/* One GI bounce (roma_gi_bounce) up to its hit's lighting: the start walk over `skip` (exact:
 * the whole ray), the snapped query, the surface search and the walk that checks the hit's
 * point (at most 64 cells long). Its lighting adds one area-light sample when there are
 * emitters and one roma_loop_cost_punctual_light per light. */
uint32_t roma_loop_cost_gi_bounce(roma_loop_grid g, float skip, int exact);

#endif /* ROMA_TRACE_LOOP_COSTS_H */
