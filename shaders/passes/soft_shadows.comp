#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Direct light from area lights (emissive triangles): spp light samples per
// pixel, drawn exactly as the reference draws them (dimensions 2-4, sample
// frame * spp + k), each with an un-snapped shadow ray of bounded steps.
// The irradiance estimates are added to accum (divide by spp * frames).
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_bindings.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaEmitters { roma_gpu_emitter e[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaFloats { float f[]; };
layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { vec4 accum[]; };

layout(push_constant) uniform Push { roma_soft_shadows_push pc; };

const uint DIM_DIRECT_AREA = 2u;

// First i with cdf[i] > u (as roma_emitter_pick).
uint pick_emitter(uint count, float u)
{
    uint lo = 0u, hi = count - 1u;
    while (lo < hi) {
        uint mid = lo + (hi - lo) / 2u;
        if (RomaFloats(pc.cdf).f[mid] > u)
            hi = mid;
        else
            lo = mid + 1u;
    }
    return lo;
}

void main()
{
    uint width = pc.config.x, height = pc.config.y, spp = pc.config.z, frame = pc.config.w;
    uint seed = pc.config2.x, emitter_count = pc.config2.y, max_steps = pc.config2.z;
    uint pixel;
    if (!roma_bound_pixel(pixel) || emitter_count == 0u)
        return;
    roma_gbuffer_pixel g = roma_gbuffer[pixel];
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 p = g.position_t.xyz, n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    float offset = pc.ray.x;
    vec3 origin = p + ng * offset;
    vec3 acc = vec3(0.0);
    for (uint k = 0u; k < spp; ++k) {
        uint s = frame * spp + k;
        roma_gpu_emitter e = RomaEmitters(pc.emitters).e[pick_emitter(emitter_count,
                                                                      roma_random(seed, pixel, s, DIM_DIRECT_AREA))];
        float su = sqrt(roma_random(seed, pixel, s, DIM_DIRECT_AREA + 1u));
        float b1 = 1.0 - su, b2 = roma_random(seed, pixel, s, DIM_DIRECT_AREA + 2u) * su;
        vec3 y = e.v0_pdf.xyz + b1 * e.e1.xyz + b2 * e.e2.xyz;
        vec3 w = y - p;
        float d2 = dot(w, w);
        if (!(d2 > 0.0))
            continue;
        w *= inversesqrt(d2);
        float cos_x = dot(n, w), cos_y = abs(dot(e.normal.xyz, w));
        if (cos_x <= 0.0 || dot(ng, w) <= 0.0 || cos_y <= 0.0)
            continue;
        // The light's end is offset off the emitter like the origin is off the
        // surface, so that segments arriving at a grazing angle do not run
        // through the cells of the emitter or of a surface just behind it.
        vec3 toward_p = dot(e.normal.xyz, w) < 0.0 ? e.normal.xyz : -e.normal.xyz;
        if (!roma_segment_visible(origin, y + toward_p * offset, 0.0, pc.ray.y, max_steps))
            continue;
        float g = min(cos_x * cos_y / (d2 * e.v0_pdf.w), ROMA_MAX_IRRADIANCE);
        acc += roma_bounded_irradiance(g, e.emission.rgb);
    }
    accum[pixel] += vec4(acc, 0.0);
}
