#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// NAADF, step 4 of 4: one invocation per mixed block (step 1's list, dispatched
// indirectly): each of its 64 voxels occupied, or the empty box around it within the block.
// The voxels of empty and full blocks are left unwritten: the traversal never reads them.
#define ROMA_NAADF_BUILD_BLOCK
#include "roma_naadf.glsl"

layout(local_size_x = ROMA_NAADF_WORKGROUP_SIZE) in;
layout(std430, binding = ROMA_NAADF_BINDING_CELLS) writeonly buffer Cells { uint cells[]; };
layout(std430, binding = ROMA_NAADF_BINDING_MIXED) readonly buffer Mixed {
    roma_naadf_mixed_header header;
    uint mixed[];
};
layout(push_constant) uniform Push { roma_naadf_push pc; };

void main()
{
    uint slot = (gl_WorkGroupID.y * ROMA_NAADF_MAX_GROUPS + gl_WorkGroupID.x) * ROMA_NAADF_WORKGROUP_SIZE +
                gl_LocalInvocationID.x;
    if (slot >= header.count)
        return;
    uint res = pc.config.x, voxel_base = roma_naadf_voxel_base(res);
    uvec2 mask = uvec2(mixed[3u * slot + 1u], mixed[3u * slot + 2u]);
    ivec3 v0 = roma_naadf_cell(mixed[3u * slot], pc.config.z) * 4;
    for (uint p = 0u; p < 32u; ++p) { // p = (y * 4 + x) * 2 + z / 2: voxels 2p and 2p + 1
        ROMA_LOOP_TICK();
        ivec3 local = ivec3(int((p >> 1) & 3u), int(p >> 3), int((p & 1u) * 2u));
        uint pair = 0u;
        for (int k = 0; k < 2; ++k) {
            ROMA_LOOP_TICK();
            uint bit = 2u * p + uint(k);
            uint voxel = 1u;
            if (((mask[bit >> 5] >> (bit & 31u)) & 1u) == 0u) {
                ivec3 pos, neg;
                roma_naadf_grow_block(mask, local + ivec3(0, 0, k), pos, neg);
                voxel = roma_naadf_pack(pos, neg, 2u, 1u);
            }
            pair |= voxel << (16u * uint(k));
        }
        cells[voxel_base + (roma_naadf_index(v0 + local, res) >> 1)] = pair;
    }
}
