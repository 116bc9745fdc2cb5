#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Copies the vertex positions an engine keeps in its own GPU memory (after its
// skinning or animation pass) into the float4 positions the voxelizer reads.
#include "roma_shared.h"

layout(local_size_x = ROMA_GATHER_WORKGROUP_SIZE) in;

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaSourceWords { float w[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RomaPositions { vec4 p[]; };

layout(push_constant) uniform Push { roma_gather_positions_push pc; };

void main()
{
    // Linear across a dispatch split into rows of 65,535 groups (roma_cmd_dispatch_linear).
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    if (i >= pc.config.x)
        return;
    RomaSourceWords src = RomaSourceWords(pc.src);
    uint at = i * pc.config.y;
    RomaPositions(pc.dst).p[i] = vec4(src.w[at], src.w[at + 1u], src.w[at + 2u], 1.0);
}
