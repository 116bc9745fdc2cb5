#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Skins every vertex of an animated scene (roma_animator): the weighted joint matrices of
// a skinned vertex, or its node's world matrix, applied to its mesh-space position.
#include "roma_shared.h"

layout(local_size_x = ROMA_SKIN_WORKGROUP_SIZE) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SkinVertices { roma_skin_vertex v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SkinRows { vec4 r[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer SkinPositions { float p[]; };

layout(push_constant) uniform Push { roma_skin_push pc; };

vec3 transform(SkinRows rows, uint m, vec4 p)
{
    return vec3(dot(rows.r[3u * m], p), dot(rows.r[3u * m + 1u], p), dot(rows.r[3u * m + 2u], p));
}

void main()
{
    // Linear across a dispatch split into rows of 65,535 groups (roma_cmd_dispatch_linear).
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    if (i >= pc.config.x)
        return;
    roma_skin_vertex v = SkinVertices(pc.vertices).v[i];
    SkinRows rows = SkinRows(pc.rows);
    vec4 p = vec4(v.rest.xyz, 1.0);
    vec3 q;
    if (v.joints.x == 0xffffffffu) {
        q = transform(rows, floatBitsToUint(v.rest.w), p);
    } else {
        uint base = pc.config.y;
        q = v.weights.x * transform(rows, base + v.joints.x, p) + v.weights.y * transform(rows, base + v.joints.y, p) +
            v.weights.z * transform(rows, base + v.joints.z, p) + v.weights.w * transform(rows, base + v.joints.w, p);
    }
    SkinPositions out_p = SkinPositions(pc.positions);
    out_p.p[3u * i] = q.x;
    out_p.p[3u * i + 1u] = q.y;
    out_p.p[3u * i + 2u] = q.z;
}
