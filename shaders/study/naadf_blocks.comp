#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// NAADF, step 1 of 4: one invocation per block of 4^3 voxels. Writes the block's state (an
// empty block's box: step 2) and lists each mixed block with its voxels for step 4.
#include "roma_naadf.glsl"

layout(local_size_x = ROMA_NAADF_WORKGROUP_SIZE) in;
layout(std430, binding = ROMA_NAADF_BINDING_BOM) readonly buffer Bom { uint bom[]; };
layout(std430, binding = ROMA_NAADF_BINDING_CELLS) writeonly buffer Cells { uint cells[]; };
layout(std430, binding = ROMA_NAADF_BINDING_MIXED) buffer Mixed { roma_naadf_mixed_header header; uint mixed[]; };
layout(push_constant) uniform Push { roma_naadf_push pc; };

void main()
{
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_NAADF_WORKGROUP_SIZE +
             gl_LocalInvocationID.x;
    if (i >= pc.config.w)
        return;
    uint res = pc.config.x, per_texel = res / 32u;
    ivec3 v0 = roma_naadf_cell(i, pc.config.z) * 4;
    // The block's voxels, (x, y, z) at bit (y * 4 + x) * 4 + z: row (x, y) is a nibble.
    uvec2 mask = uvec2(0u);
    for (int r = 0; r < 16; ++r) {
        ROMA_LOOP_TICK();
        ivec3 v = v0 + ivec3(r & 3, r >> 2, 0);
        uint word = bom[(uint(v.y) * res + uint(v.x)) * per_texel + uint(v.z >> 5)];
        mask[r >> 3] |= ((word >> uint(v.z & 31)) & 15u) << (uint(r & 7) * 4u);
    }
    uint state = mask == uvec2(0u) ? ROMA_NAADF_EMPTY : mask == uvec2(0xffffffffu) ? ROMA_NAADF_FULL : ROMA_NAADF_MIXED;
    cells[roma_naadf_block_base(res) + i] = state;
    if (state == ROMA_NAADF_MIXED) {
        uint slot = atomicAdd(header.count, 1u);
        mixed[3u * slot] = i;
        mixed[3u * slot + 1u] = mask.x;
        mixed[3u * slot + 2u] = mask.y;
    }
}
