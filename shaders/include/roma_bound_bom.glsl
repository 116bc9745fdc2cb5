// libroma's tracing passes bind the map's BOM (ROMA_PIXEL_BINDING_BOM of the trace set, or
// ROMA_BOM_SET / ROMA_BOM_BINDING) for the exact walk of their rays' start
// (roma/ray_start.glsl), as an R32_UINT uniform texel buffer (roma_map_info.bom_view): on
// CPU devices texel fetches are several times faster than storage loads at varying indices,
// which are faster than loads through an address. Include before roma/ray_start.glsl.
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

layout(set = ROMA_BOM_SET, binding = ROMA_BOM_BINDING) uniform usamplerBuffer roma_bom_texels;

#define ROMA_RAY_START_FETCH
uint roma_fetch_bom_word(uint index) { return texelFetch(roma_bom_texels, int(index)).x; }
// The whole texel, where a pass binds something else in the BOM's place (a view of 4 channels).
uvec4 roma_fetch_bom_texel(uint index) { return texelFetch(roma_bom_texels, int(index)); }

#endif // ROMA_BOUND_BOM_GLSL
