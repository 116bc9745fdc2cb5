// The covered-pixel list of a public effect's images (image_effect.c), bound in set 1
// after the map's BOM: a roma_pixel_list_header (dispatch.w: the pixels listed), then the
// pixel indices. ROMA_IMAGE_LIST_WRITER: the pass that builds it (else read-only).
#ifndef ROMA_IMAGE_LIST_GLSL
#define ROMA_IMAGE_LIST_GLSL

#include "roma_shared.h"

#define ROMA_IMAGE_LIST_BINDING 5

#ifndef ROMA_IMAGE_LIST_WRITER
readonly
#endif
layout(set = 1, binding = ROMA_IMAGE_LIST_BINDING, std430) buffer RomaImageList {
    roma_pixel_list_header header;
    uint pixels[];
} roma_image_list;

// The listed pixel of this invocation of the effect's indirect dispatch (8 x 8 workgroups
// over a 2D grid), or false past the end of the list.
bool roma_image_listed_pixel(out uint pixel)
{
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
    pixel = 0u;
    if (i >= roma_image_list.header.dispatch.w)
        return false;
    pixel = roma_image_list.pixels[i];
    return true;
}

#endif // ROMA_IMAGE_LIST_GLSL
