// The AO pass with the effect's surface grid (roma_ao_effect's ROMA_AO_START_SURFACES and
// ROMA_AO_TRACE_SURFACES, effects/ao_images_surfaces.comp and ao_images_surface_rays.comp):
// the pass (roma_ao_images.glsl) and the check of a ray's skipped start through the grid; the
// includer defines roma_ao_ray_open.
#ifndef ROMA_AO_SURFACE_START_GLSL
#define ROMA_AO_SURFACE_START_GLSL
vec3 roma_ao_point_, roma_ao_normal_;
#define ROMA_AO_BEGIN(p, ng) roma_ao_point_ = (p), roma_ao_normal_ = (ng)
#include "roma_ao_images.glsl"
#include "roma_surface_grid.glsl"

// Where the snapped query of origin + dir * [skip, ...] begins: on its column's centre line
// (through the origin's texel of its stratum's map, along the candidate), at the skip.
vec3 roma_ao_query_start(vec3 origin, vec3 dir, float skip)
{
    roma_grid_params grid = roma_fetch_grid(roma_level_of(origin));
    roma_ray_dir d = roma_ray_dir_of(dir, grid.dims.z);
    roma_map_frame f = roma_fetch_frame(grid.level.z + d.k);
    vec3 m = roma_to_map(grid, f, origin);
    vec3 c = vec3(floor(m.xy) + 0.5, d.folded ? m.z - skip * f.cell.w : m.z + skip * f.cell.w);
    vec3 b = f.map_to_bom_0.xyz * c.x + f.map_to_bom_1.xyz * c.y + f.map_to_bom_2.xyz * c.z + f.map_to_bom_3.xyz;
    return grid.origin.xyz + b * grid.origin.w;
}

// The skipped start of a ray: open when the BOM shows no occupied cell on
// origin + dir * [0, skip] (the offset origin's walk). Where it shows one, that may be a
// surface the ray crosses or only the cells of one it passes within a cell (fins closer than
// the offset, whose origin lands in the next fin's cells; a point by the edge where two walls
// meet, in the other wall's cells). With the surface grid (pc.surfaces; its cells no coarser
// than 1.5 of the BOM's at the point) the start is open when the straight segment from the
// surface point to where the query begins crosses none of the grid's triangles (the surface's
// own plane apart; over at most pc.ray.w of its cells, beyond which the ray counts as
// blocked): the query's column then begins on the point's side of every surface the grid holds
// (checked along the ray alone, tried, rays along a wall were let through where their column
// began beyond it). A ray no longer than the skip is checked along itself. Where the grid is
// coarser (a cascade level finer than it, a grid coarser than the map), the BOM decides.
bool roma_ao_start_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    if (!roma_ray_start_blocked(origin, dir, min(skip, tmax)))
        return true;
    if (pc.surfaces == uvec2(0u))
        return false;
    roma_surface_grid G = RomaSurfaceGrid(pc.surfaces).g;
    vec3 p = roma_ao_point_, ng = roma_ao_normal_;
    if (!(G.grid.w <= 1.5 * roma_fetch_grid(roma_level_of(p)).origin.w))
        return false;
    vec3 to = dir * tmax;
    if (skip < tmax)
        to = roma_ao_query_start(origin, dir, skip) - p;
    float len = length(to), covered;
    return !roma_surface_crossed(G, p, to / len, 0.01 * G.grid.w, len, vec4(ng, dot(ng, p)), int(pc.ray.w),
                                 covered) &&
           covered >= len;
}

#endif // ROMA_AO_SURFACE_START_GLSL
