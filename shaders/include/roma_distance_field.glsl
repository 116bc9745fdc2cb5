// The distance field baseline (src/study/distance_field.h): cell indexing and seed
// packing shared by its build passes, and sphere tracing for the passes that trace it.
#ifndef ROMA_DISTANCE_FIELD_GLSL
#define ROMA_DISTANCE_FIELD_GLSL

#include "roma_shared.h"

uint roma_df_index(ivec3 c, uint res) { return (uint(c.y) * res + uint(c.x)) * res + uint(c.z); }
ivec3 roma_df_cell(uint index, uint res)
{
    return ivec3(int((index / res) % res), int(index / (res * res)), int(index % res));
}
uint roma_df_pack(ivec3 c) { return uint(c.x) | (uint(c.y) << 10) | (uint(c.z) << 20); }
ivec3 roma_df_unpack(uint s) { return ivec3(int(s & 1023u), int((s >> 10) & 1023u), int(s >> 20)); }

#ifdef ROMA_DF_WORD
// Distance in cells from cell c's centre to the nearest occupied cell's centre (0: occupied).
// ROMA_DF_WORD(i): word i of the distances (two float16 per word, cell 2i in the low half).
float roma_df_cells(ivec3 c, uint res)
{
    uint i = roma_df_index(c, res);
    vec2 pair = unpackHalf2x16(ROMA_DF_WORD(i >> 1));
    return (i & 1u) != 0u ? pair.y : pair.x;
}

// Sphere tracing of the field from origin along dir for tmax (world units, +INF: to the
// grid's edge): true when the ray's point lies in an occupied cell (distance 0) within at
// most max_steps steps. Each step advances the distance of the point's cell less one cell
// (half a cell for where the point lies in its cell, half a cell from the nearest centre
// to its cell's face; not conservative towards corners, as sampled fields are not), at
// least min_step cells: a smaller minimum clips fewer corners of occupied cells and takes
// more steps. A ray that runs out of steps counts as unoccluded,
// as in the ROMA paper's baseline (64 steps).
bool roma_df_occluded(roma_grid_params grid, vec3 origin, vec3 dir, float tmax, uint max_steps, float min_step)
{
    int res = int(grid.dims.x);
    vec3 g = (origin - grid.origin.xyz) * grid.inv_cell.x;
    vec3 d = normalize(dir);
    float tg = tmax * grid.inv_cell.x, t = 0.0;
    for (uint i = 0u; i < max_steps; ++i) {
        ROMA_LOOP_TICK();
        ivec3 c = ivec3(floor(g + d * t));
        if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(res))))
            return false; // out of the grid (origins lie inside; it is convex)
        float D = roma_df_cells(c, uint(res));
        if (D == 0.0)
            return true;
        t += max(D - 1.0, min_step);
        if (t > tg)
            return false;
    }
    return false;
}
#endif

#endif // ROMA_DISTANCE_FIELD_GLSL
