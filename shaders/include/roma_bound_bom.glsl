// libroma's effects bind the map's BOM (at ROMA_BOM_SET / ROMA_BOM_BINDING, which the includer
// defines) for the exact walk of their rays' start (roma/ray_start.glsl), as an R32_UINT
// uniform texel buffer (roma_map_info.bom_view): on CPU devices texel fetches are several
// times faster than storage loads at varying indices, which are faster than loads through an
// address. Include before roma/ray_start.glsl.
#ifndef ROMA_BOUND_BOM_GLSL
#define ROMA_BOUND_BOM_GLSL

#include "roma_shared.h"

#if !defined(ROMA_BOM_SET) || !defined(ROMA_BOM_BINDING)
#error "define ROMA_BOM_SET and ROMA_BOM_BINDING before including roma_bound_bom.glsl"
#endif

layout(set = ROMA_BOM_SET, binding = ROMA_BOM_BINDING) uniform usamplerBuffer roma_bom_texels;

#define ROMA_RAY_START_FETCH
uint roma_fetch_bom_word(uint index) { return texelFetch(roma_bom_texels, int(index)).x; }
// The whole texel, where a pass binds something else in the BOM's place (a view of 4 channels).
uvec4 roma_fetch_bom_texel(uint index) { return texelFetch(roma_bom_texels, int(index)); }

#endif // ROMA_BOUND_BOM_GLSL
