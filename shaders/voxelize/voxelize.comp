#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// BOM voxelization, one invocation per triangle of the push's runs: small triangles mark
// their cells here; large ones are split into tiles and queued for voxelize_tiles.comp.
#include "roma_voxelize.glsl"

layout(local_size_x = ROMA_VOXELIZE_WORKGROUP_SIZE) in;

void main()
{
    uint id = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_VOXELIZE_WORKGROUP_SIZE
              + gl_LocalInvocationID.x;
    if (id >= pc.config.x)
        return;
    // The id-th triangle of the runs.
    uint tri = id;
    for (uint r = 0u; r < ROMA_VOXELIZE_RUNS; ++r) {
        ROMA_LOOP_TICK();
        uvec2 run = (r & 1u) == 0u ? pc.runs[r >> 1u].xy : pc.runs[r >> 1u].zw;
        if (tri < run.y) {
            tri += run.x;
            break;
        }
        tri -= run.y;
    }
    int res = int(pc.grid.dims.x);
    uint words = pc.grid.dims.y;
    roma_vox_triangle t = roma_vox_load(tri, res);
    if (!t.keep)
        return;
    ivec3 extent = t.chi - t.clo + 1;
    if (extent.x * extent.y * extent.z <= int(ROMA_VOXELIZE_BOX_CELLS)) {
        roma_vox_box(t, res, words);
        return;
    }
    if (roma_vox_queue_tiles(tri, t))
        return;
    roma_vox_columns_range(t, t.clo.x, t.chi.x, t.clo.y, t.chi.y, res, words);
}
