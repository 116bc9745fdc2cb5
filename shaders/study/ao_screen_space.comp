#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The accuracy study's screen-space AO through the public AO pass (src/study/study_ao.h):
// each ray marched against the depth the engine's position image holds (no map is read),
// and the layers of a stochastic depth map if given, bound in the BOM's place.
#include "roma_ao_images.glsl"

// A pixel of the position and geometric normal images as roma_ssao.glsl reads the
// G-buffer: its distance from the eye, +INF where it holds no surface.
roma_gbuffer_pixel roma_gbuffer_fetch(uint pixel)
{
    ivec2 at = ivec2(pixel % pc.config.x, pixel / pc.config.x);
    vec4 p = texelFetch(roma_effect_position, at, 0);
    float t = p.w > 0.0 ? distance(p.xyz, pc.eye.xyz) : 1.0 / 0.0;
    vec3 ng = normalize(texelFetch(roma_effect_geometric_normal, at, 0).xyz);
    return roma_gbuffer_pixel(vec4(p.xyz, t), vec4(0.0), vec4(ng, 0.0), vec4(0.0));
}
#include "roma_ssao.glsl"

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    return !roma_ssao_blocked(origin, dir, skip, tmax);
}
