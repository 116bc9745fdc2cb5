#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// roma_temporal_effect, step 2: one iteration of an edge-aware a-trous wavelet filter (5 x 5
// taps of the B3 spline, `step` pixels apart) where the history is shorter than
// filter_below frames; taps are weighted down where their surface leaves this pixel's
// tangent plane (relative to the pixel footprint times the step) or their normal turns
// away. Elsewhere, and on the background, the value passes through.
#include "roma_shared.h"
#include "roma_footprint.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D t_position;
layout(set = 0, binding = 1) uniform sampler2D t_normal;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D t_src;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D t_dst;

layout(push_constant) uniform Push { roma_atrous_images_push pc; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(pc.config.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 centre = imageLoad(t_src, p);
    vec4 pos = texelFetch(t_position, p, 0);
    if (!(pos.w > 0.0) || centre.a >= float(pc.config.w)) {
        imageStore(t_dst, p, centre);
        return;
    }
    int step = int(pc.config.z);
    vec3 n = texelFetch(t_normal, p, 0).xyz;
    float footprint = roma_pixel_footprint(t_position, p, size, pos.xyz);
    // A pixel alone on its surface, or without a normal: nothing to average it with.
    if (!(footprint < ROMA_FOOTPRINT_ALONE) || !(dot(n, n) > 0.0)) {
        imageStore(t_dst, p, centre);
        return;
    }
    n = normalize(n);
    footprint *= float(step);
    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec3 sum = vec3(0.0), lo = centre.rgb, hi = centre.rgb;
    float weights = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        ROMA_LOOP_TICK();
        for (int dx = -2; dx <= 2; ++dx) {
            ROMA_LOOP_TICK();
            ivec2 q = p + ivec2(dx, dy) * step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            vec4 qpos = texelFetch(t_position, q, 0);
            if (!(qpos.w > 0.0))
                continue;
            vec3 qn = texelFetch(t_normal, q, 0).xyz;
            if (!(dot(qn, qn) > 0.0))
                continue;
            qn = normalize(qn);
            float plane = abs(dot(qpos.xyz - pos.xyz, n)) / max(footprint, 1e-20);
            // cos^32 by five squarings (cheaper than pow's exp2(32 log2(x)) on any device).
            float c = max(dot(n, qn), 0.0);
            c *= c;
            c *= c;
            c *= c;
            c *= c;
            c *= c;
            float w = kernel[abs(dx)] * kernel[abs(dy)] * c * exp(-plane);
            vec3 value = imageLoad(t_src, q).rgb;
            sum += w * value;
            weights += w;
            lo = min(lo, value);
            hi = max(hi, value);
        }
    }
    // A weighted mean lies between its taps; a GPU's approximate division may not.
    imageStore(t_dst, p, vec4(weights > 0.0 ? clamp(sum / weights, lo, hi) : centre.rgb, centre.a));
}
