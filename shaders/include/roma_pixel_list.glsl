// The covered-pixel list the tracing passes run over (roma_shared.h).
#ifndef ROMA_PIXEL_LIST_GLSL
#define ROMA_PIXEL_LIST_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer RomaPixelList {
    roma_pixel_list_header header;
    uint pixels[];
};

// The pixel of this invocation (an indirect dispatch over the list, 8 x 8 workgroups),
// or false past the end of the list.
bool roma_list_pixel(uvec2 list_address, out uint pixel)
{
    pixel = 0u;
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (ROMA_PIXEL_WORKGROUP_X * ROMA_PIXEL_WORKGROUP_Y)
             + gl_LocalInvocationIndex;
    RomaPixelList list = RomaPixelList(list_address);
    if (i >= list.header.dispatch.w)
        return false;
    pixel = list.pixels[i];
    return true;
}

#endif // ROMA_PIXEL_LIST_GLSL
