#version 460
// The ray-traced stochastic depth map's miss shader: the reservoir is complete as it is.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require

#include "roma_hwrt_depth_payload.glsl"

layout(location = 0) rayPayloadInEXT HwrtDepthPayload p;

void main()
{
}
