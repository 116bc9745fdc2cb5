#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// NAADF, step 2 of 4: one workgroup per chunk, one invocation per block of it (as the
// paper's build). Each empty block gets the empty box around it within the chunk; the
// chunk gets its state (its box: step 3), and a chunk that is not empty its bit in the
// rows of chunks (cleared before this step). The first invocation also writes step 4's
// indirect dispatch from step 1's count of mixed blocks.
#define ROMA_NAADF_BUILD_BLOCK
#include "roma_naadf.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = ROMA_NAADF_BINDING_CELLS) buffer Cells { uint cells[]; };
layout(std430, binding = ROMA_NAADF_BINDING_MIXED) buffer Mixed { roma_naadf_mixed_header header; };
layout(push_constant) uniform Push { roma_naadf_push pc; };

shared uint chunk_mask[2]; // blocks that are not empty; bit (y * 4 + x) * 4 + z
shared uint full_blocks;

void main()
{
    uint chunk = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (chunk >= pc.config.w)
        return; // the whole workgroup: no barrier is skipped by part of it
    uint res = pc.config.x, l = gl_LocalInvocationID.x;
    if (l < 2u)
        chunk_mask[l] = 0u;
    if (l == 0u)
        full_blocks = 0u;
    barrier();
    ivec3 local = ivec3(int((l >> 2) & 3u), int(l >> 4), int(l & 3u));
    ivec3 block = roma_naadf_cell(chunk, pc.config.y) * 4 + local;
    uint index = roma_naadf_block_base(res) + roma_naadf_index(block, pc.config.z);
    uint state = cells[index];
    if (state != ROMA_NAADF_EMPTY)
        atomicOr(chunk_mask[l >> 5], 1u << (l & 31u));
    if (state == ROMA_NAADF_FULL)
        atomicAdd(full_blocks, 1u);
    barrier();
    if (state == ROMA_NAADF_EMPTY) {
        ivec3 pos, neg;
        roma_naadf_grow_block(uvec2(chunk_mask[0], chunk_mask[1]), local, pos, neg);
        cells[index] = ROMA_NAADF_EMPTY | roma_naadf_pack(pos, neg, 2u, 2u);
    }
    if (l != 0u)
        return;
    if (chunk == 0u) {
        uint count = (header.count + ROMA_NAADF_WORKGROUP_SIZE - 1u) / ROMA_NAADF_WORKGROUP_SIZE; // step 4's groups
        header.groups_x = min(count, ROMA_NAADF_MAX_GROUPS);
        header.groups_y = (count + ROMA_NAADF_MAX_GROUPS - 1u) / ROMA_NAADF_MAX_GROUPS;
        header.groups_z = 1u;
    }
    bool empty = chunk_mask[0] == 0u && chunk_mask[1] == 0u;
    cells[chunk] = empty ? ROMA_NAADF_EMPTY : full_blocks == 64u ? ROMA_NAADF_FULL : ROMA_NAADF_MIXED;
    if (!empty) // chunk = (y * n + x) * n + z: row chunk / n, bit z
        atomicOr(cells[roma_naadf_rows_base(res) + chunk / pc.config.y], 1u << (chunk % pc.config.y));
}
