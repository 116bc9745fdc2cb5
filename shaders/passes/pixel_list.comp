#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "roma_loop_guard.glsl"
// Lists the pixels whose G-buffer sees geometry (t finite), one invocation per pixel;
// one atomic per subgroup. The order of the list does not matter: every pass writes
// only its own pixel.
#include "roma/trace_float.glsl"
#include "roma_pixel_list.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaListGbuffer {
    roma_gbuffer_pixel p[];
};

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(push_constant) uniform Push { roma_pixel_list_push pc; };

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    uint width = pc.config.x, height = pc.config.y;
    if (xy.x >= width || xy.y >= height)
        return;
    uint pixel = xy.y * width + xy.x;
    bool covered = !roma_is_inf(RomaListGbuffer(pc.pixels).p[pixel].position_t.w);
    uint n = covered ? 1u : 0u;
    uint total = subgroupAdd(n), before = subgroupExclusiveAdd(n), base = 0u;
    RomaPixelList list = RomaPixelList(pc.list);
    if (subgroupElect() && total != 0u)
        base = atomicAdd(list.header.dispatch.w, total);
    base = subgroupBroadcastFirst(base);
    if (covered)
        list.pixels[base + before] = pixel;
}
