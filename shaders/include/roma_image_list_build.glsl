// The body of shaders/effects/image_list_*.comp, which differ in the output's format only,
// and of covered_pixels.comp (the frame's shared list, without an output).
// config.z = 0: one invocation per pixel lists those whose position image holds a surface
// (w > 0; one atomic per subgroup, the order does not matter) and writes the background into
// the others (where there is an output). config.z = 1: the first invocation turns the count into the effect's indirect
// dispatch (8 x 8 workgroups, each dimension at most 65535).
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#define ROMA_IMAGE_LIST_WRITER
#include "roma_image_list.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = ROMA_IMAGE_LIST_SET, binding = 0) uniform sampler2D roma_list_position;
#ifdef ROMA_IMAGE_LIST_OUTPUT_FORMAT
layout(set = 1, binding = 3, ROMA_IMAGE_LIST_OUTPUT_FORMAT) uniform writeonly image2D roma_list_output;
#endif

layout(push_constant) uniform Push { roma_image_list_push pc; };

void main()
{
    uint width = pc.config.x, height = pc.config.y;
    if (pc.config.z == 1u) {
        if (gl_LocalInvocationIndex != 0u)
            return;
        uint groups = (roma_image_list.header.dispatch.w + 63u) / 64u, x = min(groups, 65535u);
        roma_image_list.header.dispatch.xyz = uvec3(x, x == 0u ? 0u : (groups + x - 1u) / x, 1u);
        return;
    }
    // config.w: a resolution divisor s (bits 0-7, 0 = 1) and the traced pixel's place in each
    // s x s block (bits 8-15: x, 16-23: y): with s > 1 one invocation per block lists that
    // pixel if it is covered, and the effect's upsample writes the rest.
    uint scale = max(pc.config.w & 0xffu, 1u);
    uvec2 xy = gl_GlobalInvocationID.xy * scale + uvec2((pc.config.w >> 8) & 0xffu, (pc.config.w >> 16) & 0xffu);
    if (xy.x >= width || xy.y >= height)
        return;
    bool covered = texelFetch(roma_list_position, ivec2(xy), 0).w > 0.0;
    uint n = covered ? 1u : 0u;
    uint total = subgroupAdd(n), before = subgroupExclusiveAdd(n), base = 0u;
    if (subgroupElect() && total != 0u)
        base = atomicAdd(roma_image_list.header.dispatch.w, total);
    base = subgroupBroadcastFirst(base);
    // After the subgroup operations, so that they see the lanes the branch would have split.
    if (covered)
        roma_image_list.pixels[base + before] = (xy.y << 16u) | xy.x;
#ifdef ROMA_IMAGE_LIST_OUTPUT_FORMAT
    else if (scale == 1u)
        imageStore(roma_list_output, ivec2(xy), pc.background);
#endif
}
