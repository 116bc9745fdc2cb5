#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Batch trace of rays and hits in the caller's buffers (roma_map_record_trace), everything
// reached by address, the maps too: the path an engine that traces by address takes.
#include "roma_batch_trace.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaRays { roma_ray r[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) writeonly buffer RomaHits { roma_hit h[]; };

void main()
{
    uint i;
    if (!roma_batch_index(i))
        return;
    roma_use_addresses(pc.params, pc.maps);
    RomaHits(pc.hits).h[i] = roma_batch_trace(RomaRays(pc.rays).r[i]);
}
