/* How many cascade levels a tool asks for when the user did not say (roma-render, roma-viewer). */
#include <math.h>

#include "app_common.h"
#include "roma/map.h"

uint32_t roma_app_auto_cascades(float longest, uint32_t res, float ao_radius, float finest_extent, float *finest)
{
    /* The finest level 25 cells to the AO radius (docs/accuracy.md, "Game levels"). */
    const float edge = finest_extent > 0.0f ? finest_extent : (float)res * ao_radius / 25.0f;
    if (finest)
        *finest = edge;
    if (!(ao_radius > 0.0f) || !isfinite(ao_radius) || !(edge > 0.0f) || !isfinite(edge) || !(longest > 4.0f * edge))
        return 1u;
    uint32_t levels = (uint32_t)ceilf(log2f(longest / edge)) + 1u;
    return levels > ROMA_MAX_LEVELS ? ROMA_MAX_LEVELS : levels;
}
