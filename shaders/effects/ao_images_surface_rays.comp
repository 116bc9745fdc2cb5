#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Ambient occlusion from an engine's G-buffer images with ROMA_AO_TRACE_SURFACES
// (roma_ao_effect): the skipped start as with ROMA_AO_START_SURFACES
// (roma_ao_surface_start.glsl); past it the ray itself walked through the surface grid, each
// cell's triangles tested where its two layers hold all of them, and ROMA's map (un-snapped,
// along the ray itself) asked over each run of cells that hold more. A snapped query follows
// its stratum's candidate, not the ray, so its answer over part of the ray would be about
// another line (tried: the dragon 6% too light).
#include "roma_ao_surface_start.glsl"

// How far past a run of crowded cells the map's query reaches on either side, in the map's
// cells of the level that holds the point: the map's texels sample the ray's line, not its
// cells (0 and 2 measured within 0.5% of the dragon's mean AO of 1).
const float ROMA_AO_RUN_PAD_CELLS = 1.0;

// Whether the map shows an occupied cell on origin + dir * [a, b], the run grown by the pad
// and held within [skip, tmax] (before the skip the walk of the start decided).
bool roma_ao_run_blocked(vec3 origin, vec3 dir, float a, float b, float skip, float tmax, float pad)
{
    a = max(a - pad, skip);
    b = min(b + pad, tmax);
    if (!(b > a))
        return false;
    // Texels a 2D walk crosses over b - a in any level: at most two per cell of the finest
    // level's map, and its ends (a query that ran out of steps would count as open).
    uint steps = uint(2.0 * (b - a) / roma_fetch_grid(0u).origin.w) + 4u;
    return (roma_trace_unsnapped(origin, dir, a, b, false, steps).info & ROMA_HIT_FLAG) != 0u;
}

// Crosses the empty cube of B^3 cells whose first cell is `first` in one step: the walk goes on
// from the cell past the face the ray leaves it by (on the other axes the cell it is in, held
// within the cube against rounding). False where the segment or the grid ends inside it.
bool roma_ao_cross_empty(inout roma_surface_walk w, vec3 d, ivec3 first, int B, int n)
{
    vec3 exits = mix(vec3(1e30), (vec3(first) + vec3(greaterThan(d, vec3(0.0))) * float(B) - w.g) / w.safe, w.moves);
    float out_t = min(min(exits.x, exits.y), exits.z);
    if (out_t >= w.hi)
        return false;
    float enter = max(w.enter, out_t);
    ivec3 inside = clamp(ivec3(floor(w.g + d * enter)), first, first + ivec3(B - 1));
    ivec3 past = first + mix(ivec3(-1), ivec3(B), greaterThan(d, vec3(0.0)));
    ivec3 c = mix(inside, past, lessThanEqual(exits, vec3(out_t)));
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(n))))
        return false;
    roma_surface_walk_jump(w, c, enter);
    return true;
}

// The walk of o + d * [t0, t1] (d unit, world units) through the surface grid, over at most
// max_cells of its cells (an empty super-block of ROMA_SURFACE_SUPER^3 cells or block of
// ROMA_SURFACE_BLOCK^3 is crossed in one step, each to a cell farther along the ray: 2
// max_cells steps; beyond them, blocked); outside the grid nothing lies. A triangle a cell
// holds crossed inside it blocks (the plane `own` apart: the surface the ray leaves). Over each
// run of cells whose count shows more triangles than their two layers hold, the map decides:
// an un-snapped query from the offset origin along the ray over the run (held within [skip,
// t1], grown by pad); early_run: whether a run began before the skip (where the caller's check
// of the start decides).
bool roma_ao_surface_walk_open(roma_surface_grid G, vec3 o, vec3 d, float t0, float t1, vec4 own, int max_cells,
                               vec3 origin, float skip, float pad, out bool early_run)
{
    early_run = false;
    roma_surface_walk w;
    if (!roma_surface_walk_begin(G, o, d, t0, t1, w))
        return true; // the segment misses the grid's box
    float cs = G.grid.w;
    uint n = G.config.x, layer = n * n * n, side = (n + ROMA_SURFACE_BLOCK - 1u) / ROMA_SURFACE_BLOCK;
    uint supers = layer + side * side * side, super_side = (n + ROMA_SURFACE_SUPER - 1u) / ROMA_SURFACE_SUPER;
    const int B = int(ROMA_SURFACE_BLOCK), S = int(ROMA_SURFACE_SUPER);
    float run = -1.0; // where the current run of crowded cells began (cells), or < 0
    for (int i = 0; i < 2 * max_cells; ++i) {
        ROMA_LOOP_TICK();
        ivec3 b = w.c / B;
        if (RomaUints(G.third_cells).u[layer + (uint(b.z) * side + uint(b.y)) * side + uint(b.x)] == 0u) {
            // Empty space (most of an unbounded ray's): a crowded run ends where it begins; the
            // step crosses the block, or its super-block where that is empty too (the block's
            // flag first: a cell in a flagged block costs no more load than before).
            if (run >= 0.0) {
                if (roma_ao_run_blocked(origin, d, run * cs, w.enter * cs, skip, t1, pad))
                    return false;
                run = -1.0;
            }
            ivec3 s = w.c / S;
            bool empty_super =
                RomaUints(G.third_cells).u[supers + (uint(s.z) * super_side + uint(s.y)) * super_side + uint(s.x)] == 0u;
            if (!roma_ao_cross_empty(w, d, empty_super ? s * S : b * B, empty_super ? S : B, int(n)))
                return true;
            continue;
        }
        float enter = w.enter, leave = roma_surface_walk_leave(w);
        uint at = (uint(w.c.z) * n + uint(w.c.y)) * n + uint(w.c.x);
        // An empty cell costs one load more: its count is 0 (test_surface_cells).
        uint low = RomaUints(G.cells).u[at];
        bool crowded = false;
        if (low != ROMA_GBUFFER_NO_TRIANGLE) {
            uint count = RomaUints(G.third_cells).u[at];
            uint high = count > 1u ? RomaUints(G.cells).u[layer + at] - 1u : low;
            if (roma_surface_key_crossed(G, low, o, d, t0, t1, enter * cs, leave * cs, own) ||
                (high != low && roma_surface_key_crossed(G, high, o, d, t0, t1, enter * cs, leave * cs, own)))
                return false;
            crowded = count > 2u;
        }
        if (crowded && run < 0.0) {
            run = enter;
            early_run = early_run || enter * cs < skip;
        }
        if (!crowded && run >= 0.0) {
            if (roma_ao_run_blocked(origin, d, run * cs, enter * cs, skip, t1, pad))
                return false;
            run = -1.0;
        }
        if (!roma_surface_walk_step(w, n)) // the end of the segment or of the grid
            return !(run >= 0.0 && roma_ao_run_blocked(origin, d, run * cs, leave * cs, skip, t1, pad));
    }
    return false;
}

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    roma_surface_grid G = RomaSurfaceGrid(pc.surfaces).g;
    vec3 p = roma_ao_point_, ng = roma_ao_normal_;
    float map_cell = roma_fetch_grid(roma_level_of(p)).origin.w;
    // Where the grid is coarser than the map at the point, the start's check and the snapped
    // query decide, as with ROMA_AO_START_SURFACES; a ray no longer than its skip is checked
    // along itself there.
    if (!(G.grid.w <= 1.5 * map_cell) || skip >= tmax)
        return roma_ao_start_open(origin, dir, skip, tmax) &&
               (skip >= tmax || (roma_trace_snapped(origin, dir, skip, tmax, false).info & ROMA_HIT_FLAG) == 0u);
    // From the point itself, lifted off its surface as the reference lifts its rays' origins
    // (1e-5 of the scene's diagonal, here the grid's): from the offset origin a wall closer than
    // the offset, or a fin thinner than it, would lie behind the ray's start (2CylinderEngine
    // 0.062 against 0.037), and crossings within 1% of a cell of the point ignored let corner
    // rays through walls (13 more of the closed room's 76,800 pixels above 0.05 at 320 x 240).
    vec3 o = p + ng * (1e-5 * 1.7320508 * float(G.config.x) * G.grid.w);
    bool early_run;
    return roma_ao_surface_walk_open(G, o, dir, 0.0, tmax, vec4(ng, dot(ng, p)), int(pc.config2.y), origin, skip,
                                     ROMA_AO_RUN_PAD_CELLS * map_cell, early_run) &&
           (!early_run || roma_ao_start_open(origin, dir, skip, tmax));
}
