// G-buffer raster pass, shared by passes/gbuffer.vert and passes/gbuffer.frag.
#ifndef ROMA_GBUFFER_GLSL
#define ROMA_GBUFFER_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_camera.glsl"
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

#endif // ROMA_GBUFFER_GLSL
