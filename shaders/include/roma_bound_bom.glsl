// libroma's tracing passes bind the map's BOM (ROMA_PIXEL_BINDING_BOM of the trace set, or
// ROMA_BOM_SET / ROMA_BOM_BINDING) for the exact walk of their rays' start
// (roma/ray_start.glsl): on CPU devices bound loads are several times faster than loads
// through an address. Include before roma/ray_start.glsl.
#ifndef ROMA_BOUND_BOM_GLSL
#define ROMA_BOUND_BOM_GLSL

#include "roma_shared.h"

#ifndef ROMA_TRACE_SET
#define ROMA_TRACE_SET 0
#endif
// Where the BOM is bound: by default the tracing passes' set and binding; the public effects
// on images bind it in their images set (src/effects/image_effect.h).
#ifndef ROMA_BOM_SET
#define ROMA_BOM_SET ROMA_TRACE_SET
#endif
#ifndef ROMA_BOM_BINDING
#define ROMA_BOM_BINDING ROMA_PIXEL_BINDING_BOM
#endif

layout(std430, set = ROMA_BOM_SET, binding = ROMA_BOM_BINDING) readonly buffer RomaBoundBom {
    uint roma_bom_words[];
};

#define ROMA_RAY_START_FETCH
uint roma_fetch_bom_word(uint index) { return roma_bom_words[index]; }

#endif // ROMA_BOUND_BOM_GLSL
