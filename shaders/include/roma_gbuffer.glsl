// G-buffer raster pass, shared by study/gbuffer.vert and study/gbuffer.frag.
#ifndef ROMA_GBUFFER_GLSL
#define ROMA_GBUFFER_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_camera.glsl"
#include "roma_shared.h"
#include "roma_sampling.glsl"

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

// A stochastic depth layer drops the fragment of triangle tri at pixel pix (roma_gbuffer_push.config).
bool roma_gbuffer_dropped(uvec2 pix, uint tri)
{
    float keep = uintBitsToFloat(pc.config.y);
    if (!(keep > 0.0 && keep < 1.0) || tri == ROMA_GBUFFER_NO_TRIANGLE)
        return false;
    uint h = roma_hash_u32(roma_hash_u32(roma_hash_u32(pix.x ^ (pc.config.z * 0x9e3779b9u)) ^ pix.y) ^ tri);
    return roma_u32_to_unit_float(h) >= keep;
}

#endif // ROMA_GBUFFER_GLSL
