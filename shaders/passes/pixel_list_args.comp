#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The tracing passes' indirect dispatch from the number of listed pixels: workgroups of
// 8 x 8 over a 2D grid (each dimension is limited to 65535).
#include "roma_pixel_list.glsl"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { roma_pixel_list_push pc; };

void main()
{
    RomaPixelList list = RomaPixelList(pc.list);
    uint groups = (list.header.dispatch.w + ROMA_PIXEL_WORKGROUP_X * ROMA_PIXEL_WORKGROUP_Y - 1u) /
                  (ROMA_PIXEL_WORKGROUP_X * ROMA_PIXEL_WORKGROUP_Y);
    uint x = min(groups, 65535u);
    list.header.dispatch.xyz = uvec3(x, x == 0u ? 0u : (groups + x - 1u) / x, 1u);
}
