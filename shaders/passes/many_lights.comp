#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Visibility of many point lights (the constant-time intersection paper's use):
// per pixel, lights tested per frame are all of them (exact count) or k of
// them starting at a random light (stochastic, accumulated over frames). A
// light counts when it is in front of the shading normal and its segment is
// free in the ROMA maps (un-snapped, bounded steps). Adds (visible, tested) to
// accum; with a mask address, also writes the bit of every visible light.
#include "roma_bound_bom.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_bindings.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaPositions { vec4 p[]; };
layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { uvec2 accum[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaMask { uint w[]; };

layout(push_constant) uniform Push { roma_many_lights_push pc; };

const uint DIM_MANY_LIGHTS = 10u;

void main()
{
    uint width = pc.config.x, height = pc.config.y, light_count = pc.config.z, max_steps = pc.config.w;
    uint seed = pc.config2.x, frame = pc.config2.y, tested = min(pc.config2.z, light_count);
    uint mask_words = pc.config2.w;
    uint pixel;
    if (!roma_bound_pixel(pixel) || light_count == 0u)
        return;
    roma_gbuffer_pixel g = roma_gbuffer_fetch(pixel);
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 p = g.position_t.xyz, n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    float offset = pc.ray.x;
    vec3 origin = p + ng * offset;
    roma_use_ray_start(pc.bom);
    roma_start_walk = 1.0; // 256 segments a pixel: the four-fold walk cost 35% more here
    roma_shadow_exact = pc.ray.z > 0.0;
    // The mask is for evaluation (exact mode): every light tested, in order.
    bool write_mask = (pc.mask.x | pc.mask.y) != 0u && tested == light_count;
    uint first = tested == light_count ? 0u
                                       : min(uint(roma_random(seed, pixel, frame, DIM_MANY_LIGHTS) * float(light_count)),
                                             light_count - 1u);
    // This dispatch's part of the tested lights (src/vulkan/loop_budget.h); a part that starts
    // inside a word of the mask adds its bits to those the part before it wrote there.
    uint part_end = min(pc.part.y, tested);
    uint visible = 0u, bits = 0u;
    if (write_mask && (pc.part.x & 31u) != 0u && pc.part.x < part_end)
        bits = RomaMask(pc.mask).w[pixel * mask_words + (pc.part.x >> 5)];
    for (uint j = pc.part.x; j < part_end; ++j) {
        ROMA_LOOP_TICK();
        uint i = first + j;
        i = i >= light_count ? i - light_count : i;
        vec3 lp = RomaPositions(pc.positions).p[i].xyz;
        bool lit = dot(n, lp - p) > 0.0 &&
                   roma_punctual_visible(origin, lp - origin, false, offset, pc.ray.y, max_steps);
        visible += lit ? 1u : 0u;
        if (write_mask) {
            bits |= lit ? 1u << (i & 31u) : 0u;
            if ((i & 31u) == 31u || j + 1u == part_end) {
                RomaMask(pc.mask).w[pixel * mask_words + (i >> 5)] = bits;
                bits = 0u;
            }
        }
    }
    accum[pixel] += uvec2(visible, part_end - min(pc.part.x, part_end));
}
