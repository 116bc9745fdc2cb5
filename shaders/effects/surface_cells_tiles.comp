#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The surface grid's large triangles: one invocation per queued tile of columns
// (dispatched indirectly with the count surface_cells.comp grew).
#include "roma_surface_cells.glsl"

layout(local_size_x = ROMA_VOXELIZE_WORKGROUP_SIZE) in;

void main()
{
    uint item = gl_GlobalInvocationID.x;
    if (item >= min(queue_header.dispatch.w, pc.config.y))
        return;
    uvec2 work = queue_items[item];
    int res = int(pc.grid.dims.x);
    roma_vox_triangle t = roma_vox_load(work.x, res);
    ivec2 lo, hi;
    roma_vox_tile_columns(t, work.y, lo, hi);
    roma_surface_columns(t, work.x, lo, hi, res);
}
