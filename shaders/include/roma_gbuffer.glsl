// G-buffer raster pass, shared by passes/gbuffer.vert and passes/gbuffer.frag.
#ifndef ROMA_GBUFFER_GLSL
#define ROMA_GBUFFER_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"

layout(push_constant, std430) uniform RomaGbufferPushBlock { roma_gbuffer_push pc; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaGbufferParams {
    roma_gbuffer_params params;
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaGbufferVec4s {
    vec4 v[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaGbufferIndices {
    uint i[];
};

// Clip-space position of world point p (see roma_gbuffer_camera).
vec4 roma_gbuffer_clip(roma_gbuffer_camera cam, vec3 p)
{
    vec3 v = p - cam.eye.xyz;
    return vec4(dot(v, cam.right.xyz) * cam.right.w, -dot(v, cam.up.xyz) * cam.up.w, cam.eye.w,
                dot(v, cam.forward.xyz));
}

// Image position in pixels (pixel centres at +0.5) of world point p; z: view depth.
vec3 roma_gbuffer_pixel_of(roma_gbuffer_camera cam, vec3 p, vec2 size)
{
    vec4 c = roma_gbuffer_clip(cam, p);
    return vec3((c.xy / c.w * 0.5 + 0.5) * size, c.w);
}

#endif // ROMA_GBUFFER_GLSL
