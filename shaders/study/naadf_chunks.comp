#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// NAADF, step 3 of 4: one invocation per chunk. Each empty chunk gets the empty box around
// it within the grid, at most ROMA_NAADF_CHUNK_MAX_DISTANCE chunks a direction. Each
// workgroup first loads the chunks' occupancy rows (step 2's, at most 32 x 32 words): no
// invocation reads a chunk word another writes.
#define ROMA_NAADF_BUILD_ROWS
#include "roma_naadf.glsl"

layout(local_size_x = ROMA_NAADF_WORKGROUP_SIZE) in;
layout(std430, binding = ROMA_NAADF_BINDING_CELLS) buffer Cells { uint cells[]; };
layout(push_constant) uniform Push { roma_naadf_push pc; };

shared uint rows[32 * 32]; // chunks that are not empty: bit z of row y * n + x

uint roma_naadf_row(int x, int y) { return rows[uint(y) * pc.config.y + uint(x)]; }

void main()
{
    uint n = pc.config.y, count = pc.config.w, l = gl_LocalInvocationID.x;
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_NAADF_WORKGROUP_SIZE + l;
    uint rows_base = roma_naadf_rows_base(pc.config.x);
    for (uint r = l; r < n * n; r += ROMA_NAADF_WORKGROUP_SIZE) {
        ROMA_LOOP_TICK();
        rows[r] = cells[rows_base + r];
    }
    barrier();
    if (i >= count || cells[i] != ROMA_NAADF_EMPTY)
        return;
    ivec3 pos, neg;
    roma_naadf_grow(roma_naadf_cell(i, n), ivec3(0), ivec3(int(n) - 1), ROMA_NAADF_CHUNK_MAX_DISTANCE, pos, neg);
    cells[i] = ROMA_NAADF_EMPTY | roma_naadf_pack(pos, neg, 5u, 2u);
}
