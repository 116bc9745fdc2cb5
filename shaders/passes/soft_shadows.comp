#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Direct light from area lights (emissive triangles): spp light samples per
// pixel, drawn exactly as the reference draws them (dimensions 2-4, sample
// frame * spp + k), each with an un-snapped shadow ray of bounded steps.
// The irradiance estimates are added to accum (divide by spp * frames).
#include "roma_bound_bom.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_bindings.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { vec4 accum[]; };

layout(push_constant) uniform Push { roma_soft_shadows_push pc; };

const uint DIM_DIRECT_AREA = 2u;

void main()
{
    uint width = pc.config.x, height = pc.config.y, spp = pc.config.z, frame = pc.config.w;
    uint seed = pc.config2.x, emitter_count = pc.config2.y, max_steps = pc.config2.z;
    uint pixel;
    if (!roma_bound_pixel(pixel) || emitter_count == 0u)
        return;
    roma_gbuffer_pixel g = roma_gbuffer_fetch(pixel);
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 p = g.position_t.xyz, n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    float offset = pc.ray.x;
    vec3 origin = p + ng * offset;
    roma_use_ray_start(pc.bom);
    roma_shadow_exact = pc.ray.z > 0.0;
    vec3 acc = vec3(0.0);
    for (uint k = pc.part.x; k < min(pc.part.y, spp); ++k) { // this dispatch's part
        ROMA_LOOP_TICK();
        uint s = frame * spp + k;
        vec3 u = vec3(roma_random(seed, pixel, s, DIM_DIRECT_AREA), roma_random(seed, pixel, s, DIM_DIRECT_AREA + 1u),
                      roma_random(seed, pixel, s, DIM_DIRECT_AREA + 2u));
        acc += roma_area_sample_irradiance(RomaEmitters(pc.emitters), RomaFloats(pc.cdf), emitter_count, u, p, ng, n,
                                           origin, offset, pc.ray.y, max_steps);
    }
    accum[pixel] += vec4(acc, 0.0);
}
