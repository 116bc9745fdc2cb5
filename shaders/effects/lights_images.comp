#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Shadowed irradiance from punctual lights and area lights on an engine's G-buffer images
// (roma_light_effect): per pixel and punctual light one un-snapped shadow ray through the
// map bound at set 0; per area-light sample one more, the samples drawn as the reference
// draws them (dimensions 2-4, pixel y * width + x, sample frame * samples + k); formulas as
// passes/punctual_lights.comp, passes/soft_shadows.comp and the reference tracer.
#define ROMA_TRACE_SET 0
#include "roma_lights.glsl"
#include "roma_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform sampler2D roma_light_position;
layout(set = 1, binding = 1) uniform sampler2D roma_light_normal;
layout(set = 1, binding = 2) uniform sampler2D roma_light_geometric_normal;
layout(set = 1, binding = 3, rgba32f) uniform writeonly image2D roma_light_output;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaLights { roma_gpu_light l[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaEmitters { roma_gpu_emitter e[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaFloats { float f[]; };

layout(push_constant) uniform Push { roma_light_images_push pc; };

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
    uvec2 xy = gl_GlobalInvocationID.xy;
    uint width = pc.config.x, height = pc.config.y, light_count = pc.config.z, max_steps = pc.config.w;
    if (xy.x >= width || xy.y >= height)
        return;
    ivec2 at = ivec2(xy);
    vec4 position = texelFetch(roma_light_position, at, 0);
    if (!(position.w > 0.0)) {
        imageStore(roma_light_output, at, vec4(0.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = normalize(texelFetch(roma_light_normal, at, 0).xyz);
    vec3 ng = normalize(texelFetch(roma_light_geometric_normal, at, 0).xyz);
    float offset = pc.ray.x;
    vec3 origin = p + ng * offset;
    vec3 E = vec3(0.0);
    for (uint i = 0u; i < light_count; ++i) {
        roma_gpu_light light = RomaLights(pc.lights).l[i];
        vec3 l;
        float f = roma_punctual_factor(light, p, ng, n, l);
        if (f == 0.0)
            continue;
        bool visible;
        if (uint(light.position_type.w) == ROMA_GPU_LIGHT_DIRECTIONAL) {
            roma_hit h = roma_trace_unsnapped(origin, l, pc.ray.y, 1.0 / 0.0, false, max_steps);
            visible = (h.info & ROMA_HIT_FLAG) == 0u;
        } else {
            visible = roma_segment_visible(origin, light.position_type.xyz, offset, pc.ray.y, max_steps);
        }
        if (visible)
            E += roma_bounded_irradiance(f, light.color_intensity.rgb);
    }
    uint seed = pc.config2.x, emitter_count = pc.config2.y, samples = pc.config2.z, frame = pc.config2.w;
    if (emitter_count > 0u && samples > 0u) {
        uint pixel = xy.y * width + xy.x;
        vec3 area = vec3(0.0);
        for (uint k = 0u; k < samples; ++k) {
            uint s = frame * samples + k;
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
            // The segment ends off the emitter as it starts off the surface (soft_shadows.comp).
            vec3 toward_p = dot(e.normal.xyz, w) < 0.0 ? e.normal.xyz : -e.normal.xyz;
            if (!roma_segment_visible(origin, y + toward_p * offset, 0.0, pc.ray.y, max_steps))
                continue;
            float g = min(cos_x * cos_y / (d2 * e.v0_pdf.w), ROMA_MAX_IRRADIANCE);
            area += roma_bounded_irradiance(g, e.emission.rgb);
        }
        E += area / float(samples);
    }
    imageStore(roma_light_output, at, vec4(E, 0.0));
}
