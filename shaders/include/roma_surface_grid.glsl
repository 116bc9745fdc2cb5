// The surface grid (roma_surface_grid, roma_shared.h): the triangle a cell of a grid over the
// scene holds. The GI pass finds the surface a bounce ray's cell hit lies on; the light
// passes find where in the cells at a light's end a wall lies, which the BOM's occupied cells
// cannot tell (a lamp 1 cm above a ceiling and one 1 cm under it fill the same cells).
#ifndef ROMA_SURFACE_GRID_GLSL
#define ROMA_SURFACE_GRID_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaUints { uint u[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaSurfaceGrid { roma_surface_grid g; };

// The index of the cell at p in a layer (false outside the grid, or without one).
bool roma_surface_cell(roma_surface_grid G, vec3 p, out uint at)
{
    vec3 g = (p - G.grid.xyz) / G.grid.w;
    uvec3 c = uvec3(max(g, vec3(0.0)));
    at = (c.z * G.config.x + c.y) * G.config.x + c.x;
    return G.cells != uvec2(0u) && all(greaterThanEqual(g, vec3(0.0))) && all(lessThan(g, vec3(float(G.config.x))));
}

// The triangle the grid holds at p (its key's index), or ROMA_GBUFFER_NO_TRIANGLE (outside
// the grid too).
uint roma_surface_at(roma_surface_grid G, vec3 p)
{
    uint at;
    if (!roma_surface_cell(G, p, at))
        return ROMA_GBUFFER_NO_TRIANGLE;
    uint key = RomaUints(G.cells).u[at];
    return key == ROMA_GBUFFER_NO_TRIANGLE ? key : key & ~ROMA_SURFACE_EMITTER;
}

// Whether the cell at p holds a triangle that is not an area light (none outside the grid).
bool roma_surface_wall_at(roma_surface_grid G, vec3 p)
{
    uint at;
    if (!roma_surface_cell(G, p, at))
        return false;
    return RomaUints(G.cells).u[at] < ROMA_SURFACE_EMITTER ||
           (G.config.y >= 2u && RomaUints(G.cells).u[G.config.x * G.config.x * G.config.x + at] != 0u);
}

// The corners of triangle tri; returns its vertices' indices.
uvec3 roma_surface_triangle(roma_surface_grid G, uint tri, out vec3 a, out vec3 b, out vec3 c)
{
    uvec3 k = uvec3(RomaUints(G.indices).u[3u * tri], RomaUints(G.indices).u[3u * tri + 1u],
                    RomaUints(G.indices).u[3u * tri + 2u]);
    a = RomaVec4s(G.positions).v[k.x].xyz;
    b = RomaVec4s(G.positions).v[k.y].xyz;
    c = RomaVec4s(G.positions).v[k.z].xyz;
    return k;
}

// Where o + d * t meets the plane of triangle tri: t (NaN or infinite for a plane along d).
float roma_surface_plane_hit(roma_surface_grid G, uint tri, vec3 o, vec3 d)
{
    vec3 a, b, c;
    roma_surface_triangle(G, tri, a, b, c);
    vec3 n = cross(b - a, c - a);
    return dot(a - o, n) / dot(d, n);
}

// With a third layer (the lowest area light's key of each cell): the area light in the cell at p
// when the ray o + d * t (t > 0) meets its plane before the plane of tri, a surface found
// there (a lamp hung under a ceiling in the same cells, which the first layer ranks after the
// ceiling); otherwise tri.
uint roma_surface_nearer_emitter(roma_surface_grid G, uint tri, vec3 p, vec3 o, vec3 d)
{
    uint at;
    if (G.config.y != ROMA_SURFACE_LAYERS_EMITTERS || tri == ROMA_GBUFFER_NO_TRIANGLE || !roma_surface_cell(G, p, at))
        return tri;
    uint key = RomaUints(G.third_cells).u[at];
    uint emitter = key & ~ROMA_SURFACE_EMITTER;
    if (key == ROMA_GBUFFER_NO_TRIANGLE || emitter == tri)
        return tri;
    float t_wall = roma_surface_plane_hit(G, tri, o, d), t_light = roma_surface_plane_hit(G, emitter, o, d);
    return t_light > 0.0 && !(t_wall > 0.0 && t_wall <= t_light) ? emitter : tri;
}

// Whether o + d * (t0, t1] crosses triangle `key` (a cell's key: the index, maybe with
// ROMA_SURFACE_EMITTER) inside the cell it spans over [enter, leave] (world units along d),
// to within 1% of a cell (tol) of its edges; a triangle in the plane `own` crosses nothing.
bool roma_surface_key_crossed(roma_surface_grid G, uint key, vec3 o, vec3 d, float t0, float t1, float enter,
                              float leave, vec4 own)
{
    if (key == ROMA_GBUFFER_NO_TRIANGLE)
        return false;
    vec3 a, b, e;
    roma_surface_triangle(G, key & ~ROMA_SURFACE_EMITTER, a, b, e);
    vec3 nt = cross(b - a, e - a);
    float len = length(nt), tol = 0.01 * G.grid.w;
    nt /= len;
    if (!(len > 0.0) || (abs(dot(nt, own.xyz)) > 0.999 && abs(dot(own.xyz, a) - own.w) < tol))
        return false;
    float t = dot(a - o, nt) / dot(d, nt); // NaN or infinite for a plane along d
    if (!(t > t0 && t <= t1 && t >= enter - tol && t <= leave + tol))
        return false;
    // Inside the triangle, not on its plane beyond an edge (a level's cell can hold a wall's
    // edge and the doorway beside it): each edge's inward distance.
    vec3 q = o + d * t, e0 = b - a, e1 = e - b, e2 = a - e;
    float in0 = dot(cross(nt, e0), q - a) / length(e0), in1 = dot(cross(nt, e1), q - b) / length(e1),
          in2 = dot(cross(nt, e2), q - e) / length(e2);
    return min(in0, min(in1, in2)) >= -tol;
}

// A 3D DDA over the grid's cells along o + d * [t0, t1] (d unit, world units), in cells: c the
// cell it is in, entered at `enter`, left at roma_surface_walk_leave; hi where the segment
// leaves the grid's box.
struct roma_surface_walk {
    vec3 g, safe, next, delta;
    bvec3 moves;
    ivec3 c, step;
    float enter, hi;
};

// The walk's first cell; false where the segment misses the grid's box (an axis d does not
// move along bounds nothing, or everything when o lies outside the box on it).
bool roma_surface_walk_begin(roma_surface_grid G, vec3 o, vec3 d, float t0, float t1, out roma_surface_walk w)
{
    float cs = G.grid.w, res = float(G.config.x);
    w.g = (o - G.grid.xyz) / cs;
    w.moves = notEqual(d, vec3(0.0));
    w.safe = mix(vec3(1.0), d, w.moves);
    uvec3 off_box = uvec3(lessThan(w.g, vec3(0.0))) | uvec3(greaterThanEqual(w.g, vec3(res)));
    if (any(bvec3(off_box & uvec3(not(w.moves)))))
        return false;
    vec3 ta = -w.g / w.safe, tb = (vec3(res) - w.g) / w.safe;
    vec3 tlo = mix(vec3(-1e30), min(ta, tb), w.moves), thi = mix(vec3(1e30), max(ta, tb), w.moves);
    w.enter = max(t0 / cs, max(tlo.x, max(tlo.y, tlo.z)));
    w.hi = min(t1 / cs, min(thi.x, min(thi.y, thi.z)));
    if (!(w.hi > w.enter))
        return false;
    w.step = ivec3(sign(d));
    w.delta = mix(vec3(1e30), abs(1.0 / w.safe), w.moves);
    w.c = clamp(ivec3(floor(w.g + d * w.enter)), ivec3(0), ivec3(int(G.config.x) - 1));
    w.next = mix(vec3(1e30), (vec3(w.c) + vec3(greaterThan(d, vec3(0.0))) - w.g) / w.safe, w.moves);
    return true;
}

// Where the walk leaves its cell (or the segment ends), in cells along d.
float roma_surface_walk_leave(roma_surface_walk w)
{
    return min(min(w.next.x, w.next.y), min(w.next.z, w.hi));
}

// The walk on in cell c (a jump: the next faces recomputed), entered at `enter`.
void roma_surface_walk_jump(inout roma_surface_walk w, ivec3 c, float enter)
{
    w.c = c;
    w.enter = enter;
    w.next = mix(vec3(1e30), (vec3(c) + vec3(greaterThan(w.safe, vec3(0.0))) - w.g) / w.safe, w.moves);
}

// The next cell along d; false when the segment ends in this one or the walk leaves the grid.
bool roma_surface_walk_step(inout roma_surface_walk w, uint n)
{
    float leave = roma_surface_walk_leave(w);
    if (leave >= w.hi)
        return false;
    w.enter = leave;
    if (w.next.x <= w.next.y && w.next.x <= w.next.z) {
        w.c.x += w.step.x;
        w.next.x += w.delta.x;
    } else if (w.next.y <= w.next.z) {
        w.c.y += w.step.y;
        w.next.y += w.delta.y;
    } else {
        w.c.z += w.step.z;
        w.next.z += w.delta.z;
    }
    return all(greaterThanEqual(w.c, ivec3(0))) && all(lessThan(w.c, ivec3(int(n))));
}

// Whether o + d * (t0, t1] (d unit, world units) crosses a triangle a cell holds inside that
// cell (the lowest key of each cell, and in a grid of two layers the highest wall's), over at most
// max_cells cells of the grid from t0; `covered`: how far along d it looked (t1 when it
// looked at the whole segment: outside the grid nothing lies; 0 without a grid). A triangle
// within 1% of a cell of the plane `own` (xyz: unit normal, w: its dot with a point of the
// plane; zero: none) is the light's own (its emitter) and crosses nothing; with `own`, so do
// the cells that hold area lights only (any area light's: they are not walls, and skipping
// them spares an area-light sample a triangle's fetch in every cell of its lamp). Where more
// surfaces share a cell than its layers hold (three walls' corner), some are not seen; where
// a wall and an area light share one, the wall is (ROMA_SURFACE_EMITTER).
bool roma_surface_crossed(roma_surface_grid G, vec3 o, vec3 d, float t0, float t1, vec4 own, int max_cells,
                          out float covered)
{
    covered = G.cells == uvec2(0u) ? 0.0 : t1;
    roma_surface_walk w;
    if (G.cells == uvec2(0u) || !(t1 > t0) || !roma_surface_walk_begin(G, o, d, t0, t1, w))
        return false;
    float cs = G.grid.w;
    uint n = G.config.x, layer = G.config.y >= 2u ? n * n * n : 0u;
    bool mine_all = own != vec4(0.0);
    for (int i = 0; i < max_cells; ++i) {
        ROMA_LOOP_TICK();
        float enter = w.enter, leave = roma_surface_walk_leave(w);
        uint at = (uint(w.c.z) * n + uint(w.c.y)) * n + uint(w.c.x);
        uint low = RomaUints(G.cells).u[at];
        if (mine_all && low >= ROMA_SURFACE_EMITTER) // only area lights here (they rank last): no wall
            low = ROMA_GBUFFER_NO_TRIANGLE;
        uint high = layer > 0u ? RomaUints(G.cells).u[layer + at] - 1u : ROMA_GBUFFER_NO_TRIANGLE; // 0: none
        if (roma_surface_key_crossed(G, low, o, d, t0, t1, enter * cs, leave * cs, own) ||
            (high != low && roma_surface_key_crossed(G, high, o, d, t0, t1, enter * cs, leave * cs, own)))
            return true;
        covered = leave * cs;
        if (!roma_surface_walk_step(w, n)) {
            covered = t1; // the rest of the segment lies outside the grid, if any
            return false;
        }
    }
    return false;
}

#endif // ROMA_SURFACE_GRID_GLSL
