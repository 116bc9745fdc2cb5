#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// The example engine's own tracing pass: probe rays traced against libroma's maps with
// the public GLSL (roma/trace.glsl, maps reached by buffer address).
#include "roma/trace.glsl"

layout(local_size_x = 64) in;

struct probe_ray {
    vec4 origin;     // xyz, w: tmax
    vec4 direction;
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ProbeRays { probe_ray r[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) writeonly buffer ProbeHits { roma_hit h[]; };

layout(push_constant) uniform Push {
    uvec2 roma_params;   // roma_map_info.params_address
    uvec2 roma_maps;     // roma_map_info.maps_address
    uvec2 rays;
    uvec2 hits;
    uint count;
    uint max_steps;
} pc;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count)
        return;
    roma_use_addresses(pc.roma_params, pc.roma_maps);
    probe_ray r = ProbeRays(pc.rays).r[i];
    ProbeHits(pc.hits).h[i] = roma_trace_unsnapped(r.origin.xyz, r.direction.xyz, 0.0, r.origin.w, true, pc.max_steps);
}
