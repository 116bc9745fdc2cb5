#version 460
// The hardware ray-tracing baseline's miss shader: the ray met nothing.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require

#include "roma_hwrt_payload.glsl"

layout(location = 0) rayPayloadInEXT float hit_t;

void main()
{
    hit_t = HWRT_MISS;
}
