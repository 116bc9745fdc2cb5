/* Plain C mirror of the GPU rotation and trace (shaders/rotate/rotate_gather.comp, which the scatter rotation matches bit for bit, and
 * include/roma/trace.glsl): same parameters, same float expressions in
 * the same order, so tests can check the GPU bit for bit on a downloaded BOM. */
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

/* Trace one ray. map_override < 0: select the map from the direction; otherwise use
 * that map and fold flag (lets tests compare traces when float atan2 differs at a
 * stratum boundary). */
roma_hit roma_cpu_trace(const roma_grid_params *grid, const roma_map_frame *frames,
                        const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode,
                        uint32_t max_steps, int map_override, int folded_override);

#endif /* ROMA_CPU_MIRROR_H */
