// libroma's tracing passes bind the map's BOM (ROMA_PIXEL_BINDING_BOM of the trace set)
// for the exact walk of their rays' start (roma/ray_start.glsl): on CPU devices bound loads
// are several times faster than loads through an address. Include before roma/ray_start.glsl.
#ifndef ROMA_BOUND_BOM_GLSL
#define ROMA_BOUND_BOM_GLSL

#include "roma_shared.h"

#ifndef ROMA_TRACE_SET
#define ROMA_TRACE_SET 0
#endif

layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_BOM) readonly buffer RomaBoundBom {
    uint roma_bom_words[];
};

#define ROMA_RAY_START_FETCH
uint roma_fetch_bom_word(uint index) { return roma_bom_words[index]; }

#endif // ROMA_BOUND_BOM_GLSL
