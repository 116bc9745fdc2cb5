// libroma: roma/trace.glsl with the maps and their parameters bound as descriptors,
// for shaders that prefer descriptors to buffer addresses (on some devices, CPU
// implementations among them, address-based loads are several times slower).
//
// Set ROMA_TRACE_SET (define it before including; default 0):
//   binding 0: the maps, a uniform texel buffer of VK_FORMAT_R32_UINT
//              (roma_map_info.maps_view), read with texelFetch;
//   binding 1: the parameters, a uniform buffer (roma_map_info.params_buffer).
// roma_map_info.trace_set is such a set, written for the map, with layout
// roma_map_info.trace_set_layout.
// Unlike roma/trace.glsl by address, this file enables no extension: a shader that uses
// buffer references of its own enables GL_EXT_buffer_reference itself (roma/ray_start.glsl
// enables it for its BOM words).
#ifndef ROMA_TRACE_DESCRIPTORS_GLSL
#define ROMA_TRACE_DESCRIPTORS_GLSL

#ifndef ROMA_TRACE_SET
#define ROMA_TRACE_SET 0
#endif

#include "roma/trace_types.h"

layout(set = ROMA_TRACE_SET, binding = ROMA_TRACE_BINDING_MAPS) uniform usamplerBuffer roma_trace_maps;
layout(std140, set = ROMA_TRACE_SET, binding = ROMA_TRACE_BINDING_PARAMS) uniform RomaTraceParams {
    roma_grid_params grids[ROMA_MAX_LEVELS];
    roma_map_frame frames[ROMA_MAX_ANGULAR * ROMA_MAX_ANGULAR];
} roma_trace_params;

#define ROMA_TRACE_FETCH
uint roma_fetch_word(uint index) { return texelFetch(roma_trace_maps, int(index)).x; }
roma_grid_params roma_fetch_grid(uint level) { return roma_trace_params.grids[level]; }
roma_map_frame roma_fetch_frame(uint index) { return roma_trace_params.frames[index]; }

#include "roma/trace.glsl"

#endif // ROMA_TRACE_DESCRIPTORS_GLSL
