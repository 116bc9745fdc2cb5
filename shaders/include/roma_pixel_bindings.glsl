// The G-buffer and the covered-pixel list every tracing pass binds (roma_shared.h): set
// ROMA_TRACE_SET after the trace set's two bindings; each pass declares its accumulator
// at ROMA_PIXEL_BINDING_ACCUM with its own element type.
#ifndef ROMA_PIXEL_BINDINGS_GLSL
#define ROMA_PIXEL_BINDINGS_GLSL

#include "roma_shared.h"
#include "roma/trace_descriptors.glsl"

layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_GBUFFER) readonly buffer RomaBoundGbuffer {
    roma_gbuffer_pixel roma_gbuffer[];
};
layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_LIST) readonly buffer RomaBoundList {
    roma_pixel_list_header roma_list_header;
    uint roma_list_pixels[];
};

// The pixel of this invocation (an indirect dispatch over the list, 8 x 8 workgroups),
// or false past the end of the list.
bool roma_bound_pixel(out uint pixel)
{
    pixel = 0u;
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (ROMA_PIXEL_WORKGROUP_X * ROMA_PIXEL_WORKGROUP_Y)
             + gl_LocalInvocationIndex;
    if (i >= roma_list_header.dispatch.w)
        return false;
    pixel = roma_list_pixels[i];
    return true;
}

#endif // ROMA_PIXEL_BINDINGS_GLSL
