/* Cascade levels where the user did not choose them (roma-render, roma-viewer). */
#include <math.h>

#include "app_common.h"
#include "roma/map.h"

float roma_app_finest_extent(uint32_t res, float ao_radius)
{
    const float edge = (float)res * ao_radius / (float)ROMA_APP_FINEST_CELLS;
    return ao_radius > 0.0f && isfinite(edge) ? edge : 0.0f;
}

uint32_t roma_app_auto_cascades(float longest, uint32_t res, float ao_radius, float finest_extent, float *finest)
{
    const float edge = finest_extent > 0.0f ? finest_extent : roma_app_finest_extent(res, ao_radius);
    if (finest)
        *finest = edge;
    if (!(ao_radius > 0.0f) || !isfinite(ao_radius) || !(edge > 0.0f) || !(longest > 4.0f * edge))
        return 1u;
    uint32_t levels = (uint32_t)ceilf(log2f(longest / edge)) + 1u;
    return levels > ROMA_MAX_LEVELS ? ROMA_MAX_LEVELS : levels;
}
