#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Ambient occlusion from the G-buffer: one invocation per pixel, spp snapped
// any-hit rays through the ROMA maps; adds the unoccluded count to accum so
// that frames accumulate (the caller clears it before frame 0).
#include "roma_trace_descriptors.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_list.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaAoPixels {
    roma_gbuffer_pixel p[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaAoAccum { uint n[]; };

layout(push_constant) uniform Push { roma_ao_push pc; };

void main()
{
    uint width = pc.config.x, height = pc.config.y, spp = pc.config.z, frame = pc.config.w;
    uint pixel;
    if (!roma_list_pixel(pc.list, pixel))
        return;
    roma_gbuffer_pixel g = RomaAoPixels(pc.pixels).p[pixel];
    // Background: the caller writes AO 1 there.
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    precise vec3 origin = g.position_t.xyz + ng * pc.ray.x;
    uint seed = pc.config2.x, open = 0u;
    for (uint k = 0u; k < spp; ++k) {
        uint s = frame * spp + k; // new directions every frame, as in the reference
        vec3 local_dir = roma_cosine_hemisphere(roma_random(seed, pixel, s, 0u), roma_random(seed, pixel, s, 1u));
        vec3 dir = roma_local_to_world(n, local_dir);
        // Below the geometric surface counts as occluded, as in the reference.
        precise float below = dir.x * ng.x + dir.y * ng.y + dir.z * ng.z;
        if (below <= 0.0)
            continue;
        roma_hit h = roma_trace_snapped(origin, dir, pc.ray.z, pc.ray.y, false);
        open += (h.info & ROMA_HIT) == 0u ? 1u : 0u;
    }
    if (open != 0u)
        RomaAoAccum(pc.accum).n[pixel] += open;
}
