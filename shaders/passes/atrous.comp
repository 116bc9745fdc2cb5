#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// One iteration of an edge-aware a-trous wavelet filter: 5 x 5 taps of the B3
// spline, `step` pixels apart, each weighted down when its surface is far from
// this pixel's (relative to the pixel footprint at this distance), faces another
// way, or holds a value that differs by more than the noise expected after the
// frames this pixel has accumulated (about 0.5 / sqrt(frames) relative to the
// value, for the [0, 1] visibilities; the filter fades as the history grows).
// Background pixels pass through.
#include "roma_lights.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RomaVec4Out { vec4 v[]; };

layout(push_constant) uniform Push { roma_atrous_push pc; };

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    int width = int(pc.config.x), height = int(pc.config.y), step = int(pc.config.z);
    if (int(xy.x) >= width || int(xy.y) >= height)
        return;
    uint pixel = xy.y * uint(width) + xy.x;
    vec4 centre = RomaVec4s(pc.src).v[pixel];
    roma_gbuffer_pixel g = RomaGbufferPixels(pc.pixels).p[pixel];
    if (roma_is_inf(g.position_t.w)) {
        RomaVec4Out(pc.dst).v[pixel] = centre;
        return;
    }
    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    float sigma = pc.edge.x * g.position_t.w * float(step);
    float frames = max(centre.w, 1.0);
    float value_sigma = pc.edge.z * 0.5 * (max(max(centre.r, centre.g), centre.b) + 1e-3) / sqrt(frames);
    vec3 sum = vec3(0.0), lo = centre.rgb, hi = centre.rgb;
    float weights = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        ROMA_LOOP_TICK();
        for (int dx = -2; dx <= 2; ++dx) {
            ROMA_LOOP_TICK();
            ivec2 p = ivec2(xy) + ivec2(dx, dy) * step;
            if (p.x < 0 || p.y < 0 || p.x >= width || p.y >= height)
                continue;
            uint q = uint(p.y) * uint(width) + uint(p.x);
            roma_gbuffer_pixel h = RomaGbufferPixels(pc.pixels).p[q];
            if (roma_is_inf(h.position_t.w))
                continue;
            float w = kernel[abs(dx)] * kernel[abs(dy)];
            // Distance of the tap's surface from this pixel's tangent plane, and normal agreement.
            float d = abs(dot(h.position_t.xyz - g.position_t.xyz, g.geometric_normal.xyz));
            w *= exp(-d / max(sigma, 1e-30));
            w *= pow(max(dot(h.geometric_normal.xyz, g.geometric_normal.xyz), 0.0), pc.edge.y);
            vec3 value = RomaVec4s(pc.src).v[q].rgb;
            w *= exp(-length(value - centre.rgb) / value_sigma);
            sum += value * w;
            weights += w;
            lo = min(lo, value);
            hi = max(hi, value);
        }
    }
    // A weighted mean lies between its taps; a GPU's approximate division may not (an
    // AO of 1 averaged to 1.0000001), so the quotient is held there.
    RomaVec4Out(pc.dst).v[pixel] = vec4(weights > 0.0 ? clamp(sum / weights, lo, hi) : centre.rgb, centre.w);
}
