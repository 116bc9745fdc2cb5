#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The surface grid of the GI pass, one invocation per triangle: small triangles write
// their cells here; large ones are queued as tiles for surface_cells_tiles.comp, as the
// BOM voxelizer does. One invocation per triangle for all of them left part of a large
// triangle's cells unwritten at RES 256 on lavapipe (why is not known), and serialises the
// pass anywhere; when the queue is full the rest are written inline here, which on
// lavapipe may lose cells again (the queue holds 4 RES^2 tiles: a grid-wide wall is
// (RES/8)^2).
#include "roma_surface_cells.glsl"

layout(local_size_x = ROMA_VOXELIZE_WORKGROUP_SIZE) in;

void main()
{
    uint tri = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_VOXELIZE_WORKGROUP_SIZE
               + gl_LocalInvocationID.x;
    if (tri >= pc.config.x)
        return;
    int res = int(pc.grid.dims.x);
    roma_vox_triangle t = roma_vox_load(tri, res);
    if (!t.keep || roma_vox_queue_tiles(tri, t))
        return;
    roma_surface_columns(t, tri, t.clo.xy, t.chi.xy, res);
}
