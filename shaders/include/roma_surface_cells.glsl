// The GI pass's surface grid (src/effects/surface_cells.h), shared by
// effects/surface_cells.comp (one invocation per triangle) and
// effects/surface_cells_tiles.comp (one per queued tile of a large triangle): a
// triangle's index is written with atomicMin into every cell it overlaps (the exact
// voxelizer's test), so that a cell shared by several triangles holds the lowest index
// whatever the order the invocations ran in. The voxelizer's BOM binding holds the
// cells, one uint each, (z * RES + y) * RES + x.
#ifndef ROMA_SURFACE_CELLS_GLSL
#define ROMA_SURFACE_CELLS_GLSL

#include "roma_voxelize.glsl"

// The cells of columns [lo.x, hi.x] x [lo.y, hi.y] of the triangle's footprint.
void roma_surface_columns(roma_vox_triangle t, uint tri, ivec2 lo, ivec2 hi, int res)
{
    for (int iv = lo.y; iv <= hi.y; ++iv) {
        ROMA_LOOP_TICK();
        for (int iu = lo.x; iu <= hi.x; ++iu) {
            ROMA_LOOP_TICK();
            ivec2 span = roma_vox_column_span(t, iu, iv);
            for (int k = span.x; k <= span.y; ++k) {
                ROMA_LOOP_TICK();
                ivec3 c = ivec3(iu, iv, k);
                if (!roma_vox_overlaps(t, c))
                    continue;
                ivec3 w = roma_vox_from_columns(c, t.a);
                atomicMin(bom[(uint(w.z) * uint(res) + uint(w.y)) * uint(res) + uint(w.x)], tri);
            }
        }
    }
}

#endif // ROMA_SURFACE_CELLS_GLSL
