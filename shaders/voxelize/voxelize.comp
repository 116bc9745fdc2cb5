#version 460
#extension GL_GOOGLE_include_directive : require
// BOM voxelization, one invocation per triangle: small triangles mark their cells
// here; large ones are split into tiles and queued for voxelize_tiles.comp.
#include "roma_voxelize.glsl"

layout(local_size_x = ROMA_VOXELIZE_WORKGROUP_SIZE) in;

void main()
{
    uint tri = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_VOXELIZE_WORKGROUP_SIZE
               + gl_LocalInvocationID.x;
    if (tri >= pc.config.x)
        return;
    roma_grid_params grid = RomaVoxParams(pc.params).grid;
    int res = int(grid.dims.x);
    uint words = grid.dims.y;
    roma_vox_triangle t = roma_vox_load(tri, res);
    if (!t.keep)
        return;
    uvec2 cols = roma_vox_columns(t);
    if (cols.x * cols.y > ROMA_VOXELIZE_INLINE_COLUMNS) {
        uint tiles = ((cols.x + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE) *
                     ((cols.y + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE);
        RomaVoxQueue queue = RomaVoxQueue(pc.queue);
        uint capacity = pc.config.y;
        // Read first so that a full queue does not keep growing the counter.
        if (queue.header.dispatch.w + tiles <= capacity) {
            uint first = atomicAdd(queue.header.dispatch.w, tiles);
            if (first + tiles <= capacity) {
                for (uint i = 0u; i < tiles; ++i)
                    queue.items[first + i] = uvec2(tri, i);
                uint groups = (first + tiles + ROMA_VOXELIZE_WORKGROUP_SIZE - 1u) / ROMA_VOXELIZE_WORKGROUP_SIZE;
                atomicMax(queue.header.dispatch.x, groups);
                return;
            }
        }
        // Queue full: correct, only slower.
    }
    roma_vox_columns_range(t, t.clo[t.u], t.chi[t.u], t.clo[t.v], t.chi[t.v], res, words);
}
