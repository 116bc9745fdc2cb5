#version 460
#extension GL_GOOGLE_include_directive : require
// A consumer's own tracing pass: closest hits of a few rays against libroma's maps, read
// through the installed roma/trace_descriptors.glsl (set 0: roma_map_info.trace_set).
#define ROMA_TRACE_SET 0
#include "roma/trace_descriptors.glsl"
#include "roma/ray_start.glsl" // compiles against the installed headers (the probe's rays start at tmin 0)

layout(local_size_x = 8) in;

struct probe_ray {
    vec4 origin;    // xyz, w: tmax
    vec4 direction;
};
layout(std430, set = 1, binding = 0) buffer Probes {
    probe_ray rays[8];
    roma_hit hits[8];
};
layout(push_constant) uniform Push { uint count; } pc;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count)
        return;
    hits[i] = roma_trace_snapped(rays[i].origin.xyz, rays[i].direction.xyz, 0.0, rays[i].origin.w, true);
}
