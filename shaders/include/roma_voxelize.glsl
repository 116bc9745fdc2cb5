// Exact BOM voxelization in compute, shared by voxelize/voxelize.comp (one
// invocation per triangle) and voxelize/voxelize_tiles.comp (one per queued tile
// of a large triangle).
//
// A cell is marked when the triangle overlaps it: the separating-axis test with
// the 13 axes of a box and a triangle (3 box normals, the triangle normal, 9 edge
// cross products). Cells own half-open boxes [k, k+1)^3 in grid units
// (g = (p - origin) * inv_cell): the box tested is [0, 1 - 2^-24]^3 relative to
// the cell's lower corner. The candidates of a triangle are the columns of its
// bounding box along its dominant normal axis; in each column the plane spans at
// most two cells, so only those (one cell of margin either side) are tested.
// Atomics: one atomicOr per word along z (dominant axis z), one per cell otherwise.
#ifndef ROMA_VOXELIZE_GLSL
#define ROMA_VOXELIZE_GLSL

#include "roma_shared.h"

layout(push_constant, std430) uniform RomaVoxelizePushBlock { roma_voxelize_push pc; };

// Bound, not reached by address: on CPU devices address-based loads run one lane at a time.
layout(std430, set = 0, binding = ROMA_VOXELIZE_BINDING_POSITIONS) readonly buffer RomaVoxPositions { vec4 positions[]; };
layout(std430, set = 0, binding = ROMA_VOXELIZE_BINDING_INDICES) readonly buffer RomaVoxIndices { uint indices[]; };
layout(std430, set = 0, binding = ROMA_VOXELIZE_BINDING_BOM) buffer RomaVoxWords { uint bom[]; };
layout(std430, set = 0, binding = ROMA_VOXELIZE_BINDING_QUEUE) buffer RomaVoxQueue {
    roma_voxelize_queue queue_header;
    uvec2 queue_items[];  // (triangle, tile index)
};

// Same sine threshold as the raster path: below it a triangle has no area.
const float ROMA_VOX_DEGENERATE_SIN2 = 1e-12;
// Upper face of a cell: the largest float below 1 (half-open cells).
const float ROMA_VOX_BOX = 0.99999994;

// The triangle in its column frame: coordinates permuted cyclically so that z is its
// dominant normal axis (the separating-axis test is the same for a permuted cube), which
// keeps dynamic component indexing out of the loops.
struct roma_vox_triangle {
    vec3 g0, g1, g2;      // corners in grid units, column frame
    vec3 n;               // unnormalised normal, column frame
    vec3 e0, e1, e2;      // edges g1 - g0, g2 - g1, g0 - g2
    ivec3 clo, chi;       // candidate cells (bounding box clamped to the grid), column frame
    uint a;               // dominant world axis: column frame = (a+1, a+2, a) of the world
    bool keep;            // non-degenerate and touching the grid
};

vec3 roma_vox_to_columns(vec3 p, uint a)
{
    return a == 0u ? p.yzx : (a == 1u ? p.zxy : p);
}

ivec3 roma_vox_to_columns(ivec3 p, uint a)
{
    return a == 0u ? p.yzx : (a == 1u ? p.zxy : p);
}

ivec3 roma_vox_from_columns(ivec3 c, uint a)
{
    return a == 0u ? c.zxy : (a == 1u ? c.yzx : c);
}

roma_vox_triangle roma_vox_load(uint tri, int res)
{
    roma_vox_triangle t;
    // Same expression as the raster path and the CPU voxelizer.
    precise vec3 g0 = (positions[indices[3u * tri + 0u]].xyz - pc.grid.origin.xyz) * pc.grid.inv_cell.x;
    precise vec3 g1 = (positions[indices[3u * tri + 1u]].xyz - pc.grid.origin.xyz) * pc.grid.inv_cell.x;
    precise vec3 g2 = (positions[indices[3u * tri + 2u]].xyz - pc.grid.origin.xyz) * pc.grid.inv_cell.x;
    vec3 e1 = g1 - g0, e2 = g2 - g0;
    vec3 n = cross(e1, e2);
    // "keep if", so that NaN or Inf corners drop the triangle.
    t.keep = dot(n, n) > ROMA_VOX_DEGENERATE_SIN2 * dot(e1, e1) * dot(e2, e2);
    vec3 lo = min(g0, min(g1, g2)), hi = max(g0, max(g1, g2));
    t.keep = t.keep && all(greaterThanEqual(hi, vec3(0.0))) && all(lessThan(lo, vec3(float(res))));
    vec3 an = abs(n);
    t.a = (an.x >= an.y && an.x >= an.z) ? 0u : (an.y >= an.z ? 1u : 2u);
    t.g0 = roma_vox_to_columns(g0, t.a);
    t.g1 = roma_vox_to_columns(g1, t.a);
    t.g2 = roma_vox_to_columns(g2, t.a);
    t.e0 = t.g1 - t.g0;
    t.e1 = t.g2 - t.g1;
    t.e2 = t.g0 - t.g2;
    t.n = cross(t.e0, t.e1);
    // Clamp in float before converting: no overflow for corners far outside.
    t.clo = ivec3(clamp(floor(roma_vox_to_columns(lo, t.a)), vec3(0.0), vec3(float(res - 1))));
    t.chi = ivec3(clamp(floor(roma_vox_to_columns(hi, t.a)), vec3(0.0), vec3(float(res - 1))));
    return t;
}

// Columns of the triangle's footprint along its dominant axis.
uvec2 roma_vox_columns(roma_vox_triangle t)
{
    return uvec2(t.chi.xy - t.clo.xy + 1);
}

// True when [lo, hi] and the projection of the box [0, B]^3 on axis are disjoint. The
// box interval is built from corners (not centre +- radius), so that axis-aligned
// contacts compare equal values.
bool roma_vox_apart(vec3 axis, float lo, float hi)
{
    vec3 s = axis * ROMA_VOX_BOX;
    float box_lo = min(s.x, 0.0) + min(s.y, 0.0) + min(s.z, 0.0);
    float box_hi = max(s.x, 0.0) + max(s.y, 0.0) + max(s.z, 0.0);
    return lo > box_hi || hi < box_lo;
}

// The same for an edge axis, where the triangle projects onto [p, q] in either order
// (the edge's two corners project to one value).
bool roma_vox_apart2(vec3 axis, vec3 p, vec3 q)
{
    float dp = dot(axis, p), dq = dot(axis, q);
    return roma_vox_apart(axis, min(dp, dq), max(dp, dq));
}

// Separating-axis test of the triangle against cell c (coordinates relative to its corner).
bool roma_vox_overlaps(roma_vox_triangle t, ivec3 cell)
{
    vec3 o = vec3(cell);
    vec3 a = t.g0 - o, b = t.g1 - o, c = t.g2 - o;
    vec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
    bool apart = any(greaterThan(lo, vec3(ROMA_VOX_BOX))) || any(lessThan(hi, vec3(0.0)));
    // The plane: the corners project to one value up to rounding; use the range of all three.
    float na = dot(t.n, a), nb = dot(t.n, b), nc = dot(t.n, c);
    apart = apart || roma_vox_apart(t.n, min(na, min(nb, nc)), max(na, max(nb, nc)));
    // Box axis x edge (cross(unit_i, e)): e0 = b - a leaves a and c, e1 = c - b leaves a
    // and b, e2 = a - c leaves a and b as the distinct projections.
    apart = apart || roma_vox_apart2(vec3(0.0, -t.e0.z, t.e0.y), a, c) ||
            roma_vox_apart2(vec3(0.0, -t.e1.z, t.e1.y), a, b) || roma_vox_apart2(vec3(0.0, -t.e2.z, t.e2.y), a, b);
    apart = apart || roma_vox_apart2(vec3(t.e0.z, 0.0, -t.e0.x), a, c) ||
            roma_vox_apart2(vec3(t.e1.z, 0.0, -t.e1.x), a, b) || roma_vox_apart2(vec3(t.e2.z, 0.0, -t.e2.x), a, b);
    apart = apart || roma_vox_apart2(vec3(-t.e0.y, t.e0.x, 0.0), a, c) ||
            roma_vox_apart2(vec3(-t.e1.y, t.e1.x, 0.0), a, b) || roma_vox_apart2(vec3(-t.e2.y, t.e2.x, 0.0), a, b);
    return !apart;
}

// The cells [x, y] of column (iu, iv) that the triangle's plane can reach.
ivec2 roma_vox_column_span(roma_vox_triangle t, int iu, int iv)
{
    float plane = dot(t.n, t.g0);
    // Plane depth at the column's four corners: the cells between (plus one either
    // side, for float error) are the only candidates.
    float d00 = (plane - t.n.x * float(iu) - t.n.y * float(iv)) / t.n.z;
    float d10 = (plane - t.n.x * float(iu + 1) - t.n.y * float(iv)) / t.n.z;
    float d01 = (plane - t.n.x * float(iu) - t.n.y * float(iv + 1)) / t.n.z;
    float d11 = (plane - t.n.x * float(iu + 1) - t.n.y * float(iv + 1)) / t.n.z;
    float dmin = min(min(d00, d10), min(d01, d11)), dmax = max(max(d00, d10), max(d01, d11));
    float lo_a = float(t.clo.z), hi_a = float(t.chi.z);
    int k0 = int(clamp(floor(dmin) - 1.0, lo_a, hi_a));
    int k1 = int(clamp(floor(dmax) + 1.0, lo_a, hi_a));
    if (!(dmin == dmin) || !(dmax == dmax)) {  // NaN: test the whole range
        k0 = t.clo.z;
        k1 = t.chi.z;
    }
    return ivec2(k0, k1);
}

// The first BOM word of the cascade level being voxelized (the levels' BOMs follow each other).
uint roma_vox_bom_base(int res, uint words)
{
    return pc.grid.level.x * uint(res) * uint(res) * words;
}

// Tests the cells of column (iu, iv) that the triangle's plane can reach and marks
// the overlapped ones.
void roma_vox_column(roma_vox_triangle t, int iu, int iv, int res, uint words)
{
    ivec2 span = roma_vox_column_span(t, iu, iv);
    int k0 = span.x, k1 = span.y;
    if (t.a == 2u) {
        // Column frame = world: one texel, the bits gathered per word, one atomic per word.
        uint base = roma_vox_bom_base(res, words) + (uint(iv) * uint(res) + uint(iu)) * words;
        uint mask = 0u;
        int word = k0 >> 5;
        for (int k = k0; k <= k1; ++k) {
            ROMA_LOOP_TICK();
            if ((k >> 5) != word) {
                if (mask != 0u)
                    atomicOr(bom[base + uint(word)], mask);
                mask = 0u;
                word = k >> 5;
            }
            if (roma_vox_overlaps(t, ivec3(iu, iv, k)))
                mask |= 1u << uint(k & 31);
        }
        if (mask != 0u)
            atomicOr(bom[base + uint(word)], mask);
    } else {
        // World cell of column-frame cell (iu, iv, k): a = 0 -> (k, iu, iv); a = 1 -> (iv, k, iu).
        for (int k = k0; k <= k1; ++k) {
            ROMA_LOOP_TICK();
            if (!roma_vox_overlaps(t, ivec3(iu, iv, k)))
                continue;
            ivec3 c = t.a == 0u ? ivec3(k, iu, iv) : ivec3(iv, k, iu);
            atomicOr(bom[roma_vox_bom_base(res, words) + (uint(c.y) * uint(res) + uint(c.x)) * words + uint(c.z >> 5)],
                     1u << uint(c.z & 31));
        }
    }
}

// Small triangles: every cell of the bounding box, walked in world order with z
// innermost, so that each texel gets one atomic per word whatever the dominant axis.
void roma_vox_box(roma_vox_triangle t, int res, uint words)
{
    ivec3 lo = roma_vox_from_columns(t.clo, t.a), hi = roma_vox_from_columns(t.chi, t.a);
    for (int y = lo.y; y <= hi.y; ++y) {
        ROMA_LOOP_TICK();
        for (int x = lo.x; x <= hi.x; ++x) {
            ROMA_LOOP_TICK();
            uint base = roma_vox_bom_base(res, words) + (uint(y) * uint(res) + uint(x)) * words;
            uint mask = 0u;
            int word = lo.z >> 5;
            for (int z = lo.z; z <= hi.z; ++z) {
                ROMA_LOOP_TICK();
                if ((z >> 5) != word) {
                    if (mask != 0u)
                        atomicOr(bom[base + uint(word)], mask);
                    mask = 0u;
                    word = z >> 5;
                }
                if (roma_vox_overlaps(t, roma_vox_to_columns(ivec3(x, y, z), t.a)))
                    mask |= 1u << uint(z & 31);
            }
            if (mask != 0u)
                atomicOr(bom[base + uint(word)], mask);
        }
    }
}

// Columns [u0, u1] x [v0, v1] of the footprint.
void roma_vox_columns_range(roma_vox_triangle t, int u0, int u1, int v0, int v1, int res, uint words)
{
    for (int iv = v0; iv <= v1; ++iv) {
        ROMA_LOOP_TICK();
        for (int iu = u0; iu <= u1; ++iu) {
            ROMA_LOOP_TICK();
            roma_vox_column(t, iu, iv, res, words);
        }
    }
}

// The columns [lo.x, hi.x] x [lo.y, hi.y] of tile `tile` (row-major over
// ceil(columns / ROMA_VOXELIZE_TILE)).
void roma_vox_tile_columns(roma_vox_triangle t, uint tile, out ivec2 lo, out ivec2 hi)
{
    uvec2 cols = roma_vox_columns(t);
    uint tiles_u = (cols.x + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE;
    lo = t.clo.xy + ivec2((tile % tiles_u) * ROMA_VOXELIZE_TILE, (tile / tiles_u) * ROMA_VOXELIZE_TILE);
    hi = min(lo + ivec2(int(ROMA_VOXELIZE_TILE) - 1), t.chi.xy);
}

// The cells of tile `tile`.
void roma_vox_tile(roma_vox_triangle t, uint tile, int res, uint words)
{
    ivec2 lo, hi;
    roma_vox_tile_columns(t, tile, lo, hi);
    roma_vox_columns_range(t, lo.x, hi.x, lo.y, hi.y, res, words);
}

// A triangle whose footprint spans more than ROMA_VOXELIZE_INLINE_COLUMNS columns is
// queued as tiles for the tiles pass (indirect dispatch): true when it was. False for
// smaller ones and when the queue is full; the caller then does it inline (correct, only
// slower). pc.config.y: the queue's capacity.
bool roma_vox_queue_tiles(uint tri, roma_vox_triangle t)
{
    uvec2 cols = roma_vox_columns(t);
    if (cols.x * cols.y <= ROMA_VOXELIZE_INLINE_COLUMNS)
        return false;
    uint tiles = ((cols.x + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE) *
                 ((cols.y + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE);
    uint capacity = pc.config.y;
    // Read first so that a full queue does not keep growing the counter.
    if (queue_header.dispatch.w + tiles > capacity)
        return false;
    uint first = atomicAdd(queue_header.dispatch.w, tiles);
    if (first + tiles > capacity)
        return false;
    for (uint i = 0u; i < tiles; ++i) {
        ROMA_LOOP_TICK();
        queue_items[first + i] = uvec2(tri, i);
    }
    uint groups = (first + tiles + ROMA_VOXELIZE_WORKGROUP_SIZE - 1u) / ROMA_VOXELIZE_WORKGROUP_SIZE;
    atomicMax(queue_header.dispatch.x, groups);
    return true;
}

#endif // ROMA_VOXELIZE_GLSL
