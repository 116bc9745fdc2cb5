#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// One-bounce diffuse GI: per pixel, spp cosine-weighted bounce rays (the
// reference's dimensions 5 and 6, sample frame * spp + k) traced as snapped
// closest-hit ROMA queries. A hit is a cell, not a surface: the surface grid
// (roma_gi_scene) names the triangle in the cells around it, which gives the
// point where the ray meets that triangle's plane (roma_gi_bounce.glsl checks it
// against the BOM), its normals and its albedo.
// The light leaving that point is the direct light there, as the reference
// computes it: one area-light sample (dimensions 7-9) and every directional
// light through ROMA shadow rays; point and spot lights by shadow rays too, or
// through their reflective shadow maps (ROMA_GI_PUNCTUAL_RSM: the hit is lit
// when its RSM texel is the surface it hit, not farther from the light than that
// texel plus a tolerance, and reflects albedo/pi * E towards the pixel).
// Adds L(y) to accum (the resolve multiplies by the pixel's albedo and divides
// by spp * frames: cosine sampling cancels cos/pi).
#include "roma_bound_bom.glsl"
#include "roma_camera.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_pixel_bindings.glsl"
#include "roma_gi_bounce.glsl"
#include "roma_rsm_lookup.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { vec4 accum[]; };

layout(push_constant) uniform Push { roma_gi_push gi; };

// Which routes a frame takes, as constants so that the other is compiled out (code that
// never runs still costs a SIMD CPU device registers: the RSM route alone ran at half
// speed with the surface code present): hits find their surface in the grid and are lit
// by shadow rays (some light needs it), and point and spot lights are read from RSMs.
layout(constant_id = 0) const bool ROMA_GI_SURFACES = true;
layout(constant_id = 1) const bool ROMA_GI_RSM = true;


void main()
{
    uint width = gi.config.x, height = gi.config.y, spp = gi.config.z, frame = gi.config.w;
    uint seed = gi.config2.x;
    uint pixel;
    if (!roma_bound_pixel(pixel))
        return;
    roma_gbuffer_pixel g = roma_gbuffer_fetch(pixel);
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    vec3 origin = g.position_t.xyz + ng * gi.ray.x;
    roma_gi_scene S;
    if (ROMA_GI_SURFACES)
        S = RomaGiScene(gi.scene).s;
    roma_use_ray_start(gi.bom);
    roma_shadow_exact = gi.config2.w != 0u;
    vec3 acc = vec3(0.0);
    roma_gi_shading P = roma_gi_shading(gi.ray.x, gi.ray.w, gi.config2.z, seed, gi.lights, gi.part.zw);
    for (uint k = gi.part.x; k < min(gi.part.y, spp); ++k) { // this dispatch's part
        ROMA_LOOP_TICK();
        uint s = frame * spp + k;
        vec3 dir = roma_local_to_world(n, roma_cosine_hemisphere(roma_random(seed, pixel, s, ROMA_DIM_GI_BOUNCE),
                                                                 roma_random(seed, pixel, s, ROMA_DIM_GI_BOUNCE + 1u)));
        if (dot(dir, ng) <= 0.0)
            continue;
        bool hit;
        vec3 hit_point;
        acc += roma_gi_bounce(S, P, origin, dir, gi.ray.y, ROMA_GI_SURFACES, pixel, s, hit, hit_point);
        if (ROMA_GI_RSM && hit && gi.part.z == 0u) // the RSMs with the first lights' part
            acc += roma_rsm_radiance(hit_point, origin, gi.views, gi.config2.y, gi.ray.z, gi.lights);
    }
    accum[pixel] += vec4(acc, 0.0);
}
