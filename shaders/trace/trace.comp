#version 460
#extension GL_GOOGLE_include_directive : require
// Batch trace: one ray per invocation, for engines, tools and tests.
#include "roma_trace.glsl"

layout(local_size_x = ROMA_TRACE_WORKGROUP_SIZE) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaRays { roma_ray r[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) writeonly buffer RomaHits { roma_hit h[]; };

layout(push_constant) uniform Push { roma_trace_push pc; };

void main()
{
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_TRACE_WORKGROUP_SIZE
             + gl_LocalInvocationID.x;
    if (i >= pc.config.z)
        return;
    RomaParams params = RomaParams(pc.params);
    RomaWords maps = RomaWords(pc.maps);
    roma_ray ray = RomaRays(pc.rays).r[i];
    uint mode = pc.config.x;
    bool closest = (mode & 1u) != 0u;
    roma_hit hit = mode < 2u
        ? roma_trace_snapped(params, maps, ray.origin, ray.dir, ray.tmin, ray.tmax, closest)
        : roma_trace_unsnapped(params, maps, ray.origin, ray.dir, ray.tmin, ray.tmax, closest, pc.config.y);
    RomaHits(pc.hits).h[i] = hit;
}
