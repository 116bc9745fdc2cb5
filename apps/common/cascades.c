/* Cascade levels where the user did not choose them (roma-render, roma-viewer). */
#include <math.h>

#include "app_common.h"
#include "roma/map.h"

float roma_app_finest_extent(uint32_t res, float ao_radius)
{
    const float edge = (float)res * ao_radius / (float)ROMA_APP_FINEST_CELLS;
    return ao_radius > 0.0f && isfinite(edge) ? edge : 0.0f;
}

uint32_t roma_app_auto_cascades(const float bounds_min[3], const float bounds_max[3], const float *eye, uint32_t res,
                                float ao_radius, float finest_extent, float *finest)
{
    const float edge = finest_extent > 0.0f ? finest_extent : roma_app_finest_extent(res, ao_radius);
    if (finest)
        *finest = edge;
    float longest = 0.0f, near = 0.0f;
    for (int a = 0; a < 3; ++a) {
        longest = fmaxf(longest, bounds_max[a] - bounds_min[a]);
        if (eye) /* how far outside the box the camera is, as the levels' cubes measure it */
            near = fmaxf(near, fmaxf(bounds_min[a] - eye[a], eye[a] - bounds_max[a]));
    }
    if (!(ao_radius > 0.0f) || !isfinite(ao_radius) || !(edge > 0.0f) || !(longest > 0.0f))
        return 1u;
    /* The levels pay where the scene's nearest part lies in a level at least twice as fine as
     * one grid over the scene: the finest level for a camera inside (a game level), a coarser
     * one for a camera outside (an object in view). Unknown camera: the scene wider than four
     * finest levels. */
    float holding = edge;
    if (!eye)
        holding = 2.0f * edge;
    else
        while (holding < 2.0f * near && holding < longest)
            holding *= 2.0f;
    if (!(longest >= 2.0f * holding))
        return 1u;
    uint32_t levels = (uint32_t)ceilf(log2f(longest / edge)) + 1u;
    return levels > ROMA_MAX_LEVELS ? ROMA_MAX_LEVELS : levels;
}

uint32_t roma_app_levels_that_fit(uint32_t res, uint32_t angular, uint64_t max_storage_range)
{
    const uint64_t level_bytes = (uint64_t)res * res * res / 8u * angular * angular;
    const uint64_t by_maps = angular ? 256u / ((uint64_t)angular * angular) : 0u;
    const uint64_t by_bytes = level_bytes ? max_storage_range / level_bytes : by_maps;
    return (uint32_t)(by_bytes < by_maps ? by_bytes : by_maps);
}
