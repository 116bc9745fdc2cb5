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
    uvec2 cols = roma_vox_columns(t);
    if (cols.x * cols.y > ROMA_VOXELIZE_INLINE_COLUMNS) {
        uint tiles = ((cols.x + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE) *
                     ((cols.y + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE);
        uint capacity = pc.config.y;
        // Read first so that a full queue does not keep growing the counter.
        if (queue_header.dispatch.w + tiles <= capacity) {
            uint first = atomicAdd(queue_header.dispatch.w, tiles);
            if (first + tiles <= capacity) {
                for (uint i = 0u; i < tiles; ++i)
                    queue_items[first + i] = uvec2(tri, i);
                uint groups = (first + tiles + ROMA_VOXELIZE_WORKGROUP_SIZE - 1u) / ROMA_VOXELIZE_WORKGROUP_SIZE;
                atomicMax(queue_header.dispatch.x, groups);
                return;
            }
        }
        // Queue full: correct, only slower.
    }
    roma_vox_columns_range(t, t.clo.x, t.chi.x, t.clo.y, t.chi.y, res, words);
}
