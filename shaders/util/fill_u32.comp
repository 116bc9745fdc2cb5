#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Fills a buffer with an arithmetic sequence; used by the device self-test and
// to clear or initialise buffers without a host round trip.
#include "roma_shared.h"

layout(local_size_x = ROMA_FILL_WORKGROUP_SIZE) in;

layout(std430, binding = ROMA_FILL_BINDING_OUTPUT) writeonly buffer Output { uint words[]; } out_buf;

layout(push_constant) uniform Push { roma_fill_push p; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < p.count)
        out_buf.words[i] = p.value + i * p.stride;
}
