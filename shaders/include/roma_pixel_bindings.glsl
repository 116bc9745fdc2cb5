// The G-buffer and the covered-pixel list every tracing pass binds (roma_shared.h): set
// ROMA_TRACE_SET after the trace set's two bindings; each pass declares its accumulator
// at ROMA_PIXEL_BINDING_ACCUM with its own element type.
#ifndef ROMA_PIXEL_BINDINGS_GLSL
#define ROMA_PIXEL_BINDINGS_GLSL

#include "roma_shared.h"
#include "roma/trace_descriptors.glsl"

layout(set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_GBUFFER) uniform samplerBuffer roma_gbuffer_texels;
// The header's 4 words, then the pixel indices.
layout(set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_LIST) uniform usamplerBuffer roma_list_texels;

roma_gbuffer_pixel roma_gbuffer_fetch(uint pixel)
{
    int at = int(pixel) * 4;
    return roma_gbuffer_pixel(texelFetch(roma_gbuffer_texels, at), texelFetch(roma_gbuffer_texels, at + 1),
                              texelFetch(roma_gbuffer_texels, at + 2), texelFetch(roma_gbuffer_texels, at + 3));
}

// The pixel of this invocation (an indirect dispatch over the list, 8 x 8 workgroups),
// or false past the end of the list.
bool roma_bound_pixel(out uint pixel)
{
    pixel = 0u;
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (ROMA_PIXEL_WORKGROUP_X * ROMA_PIXEL_WORKGROUP_Y)
             + gl_LocalInvocationIndex;
    if (i >= texelFetch(roma_list_texels, 3).x) // the header's dispatch.w
        return false;
    pixel = texelFetch(roma_list_texels, int(i) + 4).x;
    return true;
}

#endif // ROMA_PIXEL_BINDINGS_GLSL
