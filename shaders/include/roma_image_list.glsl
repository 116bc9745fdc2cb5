// The covered-pixel list of a public effect's images (image_effect.c), bound in set 1
// after the map's BOM: a roma_pixel_list_header (dispatch.w: the pixels listed), then the
// pixels, each (y << 16) | x: an effect needs both its coordinates and its index, and a CPU
// device divides (index / width) lane by lane. ROMA_IMAGE_LIST_WRITER: the pass that builds
// it (else read-only, and the effect's pixel from the list or the grid).
#ifndef ROMA_IMAGE_LIST_GLSL
#define ROMA_IMAGE_LIST_GLSL

#include "roma_shared.h"

// An effect's set 1 holds it after its images and the BOM; the frame's shared list
// (roma_pixel_list, covered_pixels.comp) has a set of its own.
#ifndef ROMA_IMAGE_LIST_SET
#define ROMA_IMAGE_LIST_SET 1
#define ROMA_IMAGE_LIST_BINDING 5
#endif

#ifndef ROMA_IMAGE_LIST_WRITER
readonly
#endif
layout(set = ROMA_IMAGE_LIST_SET, binding = ROMA_IMAGE_LIST_BINDING, std430) buffer RomaImageList {
    roma_pixel_list_header header;
    uint pixels[];
} roma_image_list;

#ifndef ROMA_IMAGE_LIST_WRITER
// Whether the effect traces the list (an indirect dispatch over it, 8 x 8 workgroups over a
// 2D grid) or every pixel (a dispatch over the images): image_effect.c's choice.
layout(constant_id = 0) const uint ROMA_IMAGE_LISTED = 1u;

// The pixel of this invocation, as its index y * width + x and as (x, y), or false past the end
// of the list or the images.
bool roma_image_pixel(uint width, uint height, out uint pixel, out ivec2 at)
{
    pixel = 0u;
    at = ivec2(0);
    if (ROMA_IMAGE_LISTED == 0u) {
        uvec2 xy = gl_GlobalInvocationID.xy;
        pixel = xy.y * width + xy.x;
        at = ivec2(xy);
        return xy.x < width && xy.y < height;
    }
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
    if (i >= roma_image_list.header.dispatch.w)
        return false;
    uint packed = roma_image_list.pixels[i];
    at = ivec2(packed & 0xffffu, packed >> 16u);
    pixel = uint(at.y) * width + uint(at.x);
    return true;
}
#endif

#endif // ROMA_IMAGE_LIST_GLSL
