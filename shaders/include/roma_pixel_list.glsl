// The covered-pixel list, as the passes that build it reach it (by address; roma_shared.h).
// The tracing passes bind it instead (roma_pixel_bindings.glsl).
#ifndef ROMA_PIXEL_LIST_GLSL
#define ROMA_PIXEL_LIST_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer RomaPixelList {
    roma_pixel_list_header header;
    uint pixels[];
};

#endif // ROMA_PIXEL_LIST_GLSL
