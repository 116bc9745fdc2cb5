#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// BOM voxelization of large triangles: one invocation per queued tile of columns
// (dispatched indirectly with the count voxelize.comp grew).
#include "roma_voxelize.glsl"

layout(local_size_x = ROMA_VOXELIZE_WORKGROUP_SIZE) in;

void main()
{
    uint item = gl_GlobalInvocationID.x;
    if (item >= min(queue_header.dispatch.w, pc.config.y))
        return;
    uvec2 work = queue_items[item];
    int res = int(pc.grid.dims.x);
    roma_vox_triangle t = roma_vox_load(work.x, res);
    roma_vox_tile(t, work.y, res, pc.grid.dims.y);
}
