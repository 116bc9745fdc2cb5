#version 460
#extension GL_GOOGLE_include_directive : require
// The surface grid of the GI pass (roma_gi_scene): one invocation per triangle
// writes its index into every cell it overlaps (the exact voxelizer's test) with
// atomicMin, so a cell shared by several triangles holds the lowest index
// whatever the order the invocations ran in. The voxelizer's BOM binding holds
// the cells here, one uint each, (z * RES + y) * RES + x.
#include "roma_voxelize.glsl"

layout(local_size_x = ROMA_VOXELIZE_WORKGROUP_SIZE) in;

void main()
{
    uint tri = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_VOXELIZE_WORKGROUP_SIZE
               + gl_LocalInvocationID.x;
    if (tri >= pc.config.x)
        return;
    int res = int(pc.grid.dims.x);
    roma_vox_triangle t = roma_vox_load(tri, res);
    if (!t.keep)
        return;
    for (int iv = t.clo.y; iv <= t.chi.y; ++iv)
        for (int iu = t.clo.x; iu <= t.chi.x; ++iu) {
            ivec2 span = roma_vox_column_span(t, iu, iv);
            for (int k = span.x; k <= span.y; ++k) {
                ivec3 c = ivec3(iu, iv, k);
                if (!roma_vox_overlaps(t, c))
                    continue;
                ivec3 w = roma_vox_from_columns(c, t.a);
                atomicMin(bom[(uint(w.z) * uint(res) + uint(w.y)) * uint(res) + uint(w.x)], tri);
            }
        }
}
