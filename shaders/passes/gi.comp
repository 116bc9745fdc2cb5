#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// One-bounce diffuse GI: per pixel, spp cosine-weighted bounce rays (the
// reference's dimensions 5 and 6, sample frame * spp + k) traced as snapped
// closest-hit ROMA queries. The hit point is looked up in the reflective shadow
// map of every point/spot light: when the RSM texel it projects to is the
// surface it hit (not farther from the light than that texel, plus a tolerance),
// that texel is lit and reflects albedo/pi * E towards the pixel.
// Adds L(y) to accum (the resolve multiplies by the pixel's albedo and divides
// by spp * frames: cosine sampling cancels cos/pi).
#include "roma_camera.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_bindings.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaLights { roma_gpu_light l[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaViews { roma_rsm_view v[]; };
layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { vec4 accum[]; };

layout(push_constant) uniform Push { roma_gi_push gi; };

const uint DIM_GI_BOUNCE = 5u;
const float INV_PI = 0.31830988618379067;

// Radiance leaving hit point h towards the bounce ray's origin, from all RSMs.
vec3 rsm_radiance(vec3 h)
{
    vec3 L = vec3(0.0);
    uint view_count = gi.config2.y;
    float tolerance = gi.ray.z;
    for (uint v = 0u; v < view_count; ++v) {
        roma_rsm_view view = RomaViews(gi.views).v[v];
        float size = float(view.info.y);
        vec3 q = roma_gbuffer_pixel_of(view.camera, h, vec2(size));
        if (!(q.z > 0.0) || q.x < 0.0 || q.y < 0.0 || q.x >= size || q.y >= size)
            continue;
        uint texel = uint(q.y) * view.info.y + uint(q.x);
        roma_gbuffer_pixel y = RomaGbufferPixels(view.info.zw).p[texel];
        if (roma_is_inf(y.position_t.w))
            continue;
        roma_gpu_light light = RomaLights(gi.lights).l[view.info.x];
        vec3 lp = light.position_type.xyz;
        // Shadow-map test: h is lit when it is no farther from the light than the surface the light sees.
        if (distance(lp, h) > distance(lp, y.position_t.xyz) + tolerance)
            continue;
        vec3 l;
        float f = roma_punctual_factor(light, y.position_t.xyz, y.geometric_normal.xyz, y.shading_normal.xyz, l);
        L += y.albedo.rgb * INV_PI * roma_bounded_irradiance(f, light.color_intensity.rgb);
    }
    return L;
}

void main()
{
    uint width = gi.config.x, height = gi.config.y, spp = gi.config.z, frame = gi.config.w;
    uint seed = gi.config2.x;
    uint pixel;
    if (!roma_bound_pixel(pixel))
        return;
    roma_gbuffer_pixel g = roma_gbuffer[pixel];
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    vec3 origin = g.position_t.xyz + ng * gi.ray.x;
    vec3 acc = vec3(0.0);
    for (uint k = 0u; k < spp; ++k) {
        uint s = frame * spp + k;
        vec3 dir = roma_local_to_world(n, roma_cosine_hemisphere(roma_random(seed, pixel, s, DIM_GI_BOUNCE),
                                                                 roma_random(seed, pixel, s, DIM_GI_BOUNCE + 1u)));
        if (dot(dir, ng) <= 0.0)
            continue;
        roma_hit h = roma_trace_snapped(origin, dir, gi.ray.y, 1.0 / 0.0, true);
        if ((h.info & ROMA_HIT_FLAG) == 0u)
            continue;
        // A snapped ray travels along its candidate direction (reversed when folded).
        vec3 cand = roma_fetch_frame((h.info >> 8) & 0xffu).dir.xyz * ((h.info & 0x10000u) != 0u ? -1.0 : 1.0);
        acc += rsm_radiance(origin + cand * h.t);
    }
    accum[pixel] += vec4(acc, 0.0);
}
