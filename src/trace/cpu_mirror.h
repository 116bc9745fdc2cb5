/* Plain C mirror of the GPU rotation and trace (shaders/rotate/rotate_gather.comp, which the
 * scatter rotation matches bit for bit, and include/roma/trace.glsl): same parameters, same
 * float expressions in the same order, so tests can check the GPU bit for bit on a
 * downloaded BOM. */
#ifndef ROMA_CPU_MIRROR_H
#define ROMA_CPU_MIRROR_H

#include <stdint.h>

#include "roma/map.h"
#include "roma_shared.h"

/* Fills maps (map_count*RES*RES*W words) from bom (RES*RES*W words). */
void roma_cpu_rotate(const roma_grid_params *grid, const roma_map_frame *frames,
                     const uint32_t *bom, uint32_t *maps);

/* Map selection exactly as roma_select_map in GLSL (C float functions). */
uint32_t roma_cpu_select_map(const float dir[3], uint32_t angular, int *folded);

/* How far a device's map selection may stray from the mirror's, in the square's units (u, v
 * in [0, 1]), from what Vulkan requires of the GLSL it runs (roma_hemisphere_to_square):
 * atan's 4096 ULP of an angle of at most pi (9.77e-4 rad) move the square's coordinate by
 * 4 / pi of that in [-1, 1], half of it in [0, 1] (6.22e-4); sqrt (1 / inversesqrt, 2 ULP)
 * and the divisions (2.5 ULP) a few ULP of r <= 1 more (about 1e-6). */
#define ROMA_CPU_SELECTION_TOLERANCE 6.3e-4f

/* Whether map gpu_map (the same fold) may be a device's selection for dir where the mirror
 * selects another: a neighbouring stratum across an edge within ROMA_CPU_SELECTION_TOLERANCE
 * of the mirror's (u, v); *distance (may be NULL): that distance in the square's units (the
 * largest of the axes that differ; 0 where the maps are equal, +INF where not neighbours). */
int roma_cpu_selection_may_differ(const float dir[3], uint32_t angular, uint32_t gpu_map, float *distance);

/* Trace one ray. map_override < 0: select the map from the direction; otherwise use
 * that map and fold flag (lets tests compare traces when float atan2 differs at a
 * stratum boundary). */
roma_hit roma_cpu_trace(const roma_grid_params *grid, const roma_map_frame *frames,
                        const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode,
                        uint32_t max_steps, int map_override, int folded_override);

/* What the un-snapped walks of roma_cpu_trace_counted met, summed over calls, so that a
 * test can show its rays reach every branch of the walk it compares the GPU on. */
typedef struct roma_cpu_walk_counts {
    uint64_t steps_ahead; /* columns where a cell past the ray's exit started a wall's step ahead */
    uint64_t back_hits;   /* rays blocked by a cell the next column's search back found before its entry */
    uint64_t unseen_hits; /* rays blocked because that search back left the map with no cell found */
} roma_cpu_walk_counts;

/* roma_cpu_trace, adding to *counts (may be NULL) what an un-snapped walk met. */
roma_hit roma_cpu_trace_counted(const roma_grid_params *grid, const roma_map_frame *frames,
                                const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode,
                                uint32_t max_steps, int map_override, int folded_override,
                                roma_cpu_walk_counts *counts);

/* A map of several cascade levels (roma_trace_snapped and roma_trace_unsnapped in GLSL): the
 * levels' grids, every level's frames and maps (level after level, as the map holds them).
 * map_override, folded_override: as for roma_cpu_trace (the same map in every level). */
roma_hit roma_cpu_trace_levels(uint32_t levels, const roma_grid_params *grids, const roma_map_frame *frames,
                               const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode, uint32_t max_steps,
                               int map_override, int folded_override);

#endif /* ROMA_CPU_MIRROR_H */
