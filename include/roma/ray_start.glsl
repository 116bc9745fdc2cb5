// libroma: the start of a ray that leaves a surface, walked exactly through the map's base
// occupancy map (BOM, a 3D DDA, Amanatides-Woo) over the distance a ROMA query skips (its
// tmin).
//
// ROMA queries skip their first trace cells because the rotated maps smear a surface over
// about a trace cell around it, so a ray would meet the cells of the surface it leaves. A
// wall within that distance is skipped too: in a closed room, rays starting next to a
// corner pass through the other wall (light leaks, bright seams). The BOM has no smear: a
// ray offset off its surface (roma_offset_origin, 1.5 trace cells = 2.6 BOM cells, above the
// cells a plane occupies) meets no cell of its own surface on the skipped part, so an
// occupied BOM cell there is another surface and blocks the ray (an offset below about one
// trace cell would let the walk meet the surface's own cells and block rays wrongly):
//
//     roma_use_ray_start(pc.roma_bom);                 // roma_map_info.bom_address, as uvec2
//     if (!roma_ray_start_blocked(origin, dir, tmin))  // tmin: the skip of the query below
//         h = roma_trace_snapped(origin, dir, tmin, tmax, false);
//
// Include after roma/trace.glsl or roma/trace_descriptors.glsl (the grid comes through
// roma_fetch_grid(level)). The BOM's words come by address, or through your own
//     uint roma_fetch_bom_word(uint index);
// defined before including this file with ROMA_RAY_START_FETCH defined (then any non-zero
// value given to roma_use_ray_start turns the walk on), for example a texelFetch from a
// usamplerBuffer bound to roma_map_info.bom_view (on CPU devices the fastest). BOM layout: one
// BOM per cascade level, level after level, each RES x RES texels of RES / 32 words, texel
// (x, y) at word (y * RES + x) * (RES / 32); cell z is bit z % 32 of the texel's word z / 32;
// cell (x, y, z) covers grid.origin + [x, x+1) * cell size, ...
// (roma_grid_params, this frame's placement). Valid after the build that wrote it, like
// the maps.
#ifndef ROMA_RAY_START_GLSL
#define ROMA_RAY_START_GLSL

#include "roma/trace_types.h"

// Each loop's body starts with ROMA_LOOP_TICK(), a hook for libroma's own iteration
// counting (its loop-guard build); nothing unless defined before including.
#ifndef ROMA_LOOP_TICK
#define ROMA_LOOP_TICK()
#endif

#ifndef ROMA_RAY_START_FETCH
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaBomWords { uint w[]; };
#endif

uvec2 roma_start_bom_ = uvec2(0u);
roma_grid_params roma_start_grid_; // the finest level's

// bom: the BOM's address (roma_map_info.bom_address; with ROMA_RAY_START_FETCH, any
// non-zero value); 0 turns the walk off.
void roma_use_ray_start(uvec2 bom)
{
    roma_start_bom_ = bom;
    roma_start_grid_ = roma_fetch_grid(0u);
}

#ifndef ROMA_RAY_START_FETCH
uint roma_fetch_bom_word(uint index) { return RomaBomWords(roma_start_bom_).w[index]; }
#endif

// Distance along normalize(dir) at which origin + normalize(dir) * [0, tmax] enters its
// first BOM cell that is occupied (occupied true) or free (false), or -1 when it meets none
// within max_cells cells (the exact voxel traversal of the BOM, Amanatides-Woo: the same
// voxels as ROMA without snapping, rotation or bounded steps), in the BOM of the cascade
// level that holds the origin, up to that level's edge (outside the grid counts as neither).
float roma_bom_walk_until(vec3 origin, vec3 dir, float tmax, int max_cells, bool occupied)
{
    if (roma_start_bom_ == uvec2(0u) || !(tmax > 0.0))
        return -1.0;
    uint level = roma_level_of(origin);
    roma_grid_params grid = ROMA_CASCADES ? roma_fetch_grid(level) : roma_start_grid_; // the one kept for one level
    float inv_cell = grid.inv_cell.x;
    int res = int(grid.dims.x);
    uint per_texel = grid.dims.y;
    uint bom_base = level * uint(res) * uint(res) * per_texel; // the levels' BOMs, one after the other
    vec3 g = (origin - grid.origin.xyz) * inv_cell;
    vec3 d = normalize(dir);
    float tg = tmax * inv_cell; // grid units
    ivec3 cell = ivec3(floor(g));
    ivec3 step = ivec3(sign(d));
    vec3 inv = 1.0 / abs(d); // +inf on axis-parallel components
    vec3 next = (vec3(cell) + max(vec3(step), vec3(0.0)) - g) / d;
    next = vec3(d.x != 0.0 ? next.x : 1.0 / 0.0, d.y != 0.0 ? next.y : 1.0 / 0.0, d.z != 0.0 ? next.z : 1.0 / 0.0);
    // The cells a segment crosses: one per step of its end cell's index from the start's,
    // plus the first (SIMD devices run every lane to the group's largest count, so the
    // exact count, not a bound); an unbounded ray leaves the grid within 3 * RES + 1.
    int cells = 3 * res + 1;
    if (tg < float(3 * res)) {
        ivec3 last = ivec3(floor(g + d * tg));
        cells = abs(last.x - cell.x) + abs(last.y - cell.y) + abs(last.z - cell.z) + 1;
    }
    cells = min(cells, max_cells);
    float t = 0.0;
    bool entered = false;
    for (int i = 0; i < cells && t <= tg; ++i) {
        ROMA_LOOP_TICK();
        bool inside = all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(cell, ivec3(res)));
        if (!inside && entered)
            break; // out of the grid for good: it is convex
        entered = entered || inside;
        if (inside) {
            uint word =
                roma_fetch_bom_word(bom_base + (uint(cell.y) * uint(res) + uint(cell.x)) * per_texel + uint(cell.z >> 5));
            if (((word & (1u << uint(cell.z & 31))) != 0u) == occupied)
                return t / inv_cell;
        }
        if (next.x <= next.y && next.x <= next.z) {
            t = next.x;
            next.x += inv.x;
            cell.x += step.x;
        } else if (next.y <= next.z) {
            t = next.y;
            next.y += inv.y;
            cell.y += step.y;
        } else {
            t = next.z;
            next.z += inv.z;
            cell.z += step.z;
        }
    }
    return -1.0;
}

// Distance at which origin + normalize(dir) * [0, tmax] enters its first occupied BOM cell,
// or -1 (roma_bom_walk_until).
float roma_bom_walk(vec3 origin, vec3 dir, float tmax, int max_cells)
{
    return roma_bom_walk_until(origin, dir, tmax, max_cells, true);
}

// The skipped start of a ray (tmax: the skip): the walk above, at most 64 cells.
float roma_ray_start_hit(vec3 origin, vec3 dir, float tmax)
{
    return roma_bom_walk(origin, dir, tmax, 64);
}

// True when an occupied BOM cell lies on origin + normalize(dir) * [0, tmax].
bool roma_ray_start_blocked(vec3 origin, vec3 dir, float tmax)
{
    return roma_ray_start_hit(origin, dir, tmax) >= 0.0;
}

#endif // ROMA_RAY_START_GLSL
