#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Places one instance of a mesh (roma_map_add_instance): its local vertices through its
// 3x4 transform into the positions the voxelizer reads.
#include "roma_shared.h"

layout(local_size_x = ROMA_GATHER_WORKGROUP_SIZE) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaLocal { vec4 p[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RomaWorld { vec4 p[]; };

layout(push_constant) uniform Push { roma_instance_push pc; };

void main()
{
    // Linear across a dispatch split into rows of 65,535 groups (roma_cmd_dispatch_linear).
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    if (i >= pc.config.x)
        return;
    vec4 p = vec4(RomaLocal(pc.src).p[i].xyz, 1.0);
    RomaWorld(pc.dst).p[i] = vec4(dot(pc.row0, p), dot(pc.row1, p), dot(pc.row2, p), 1.0);
}
