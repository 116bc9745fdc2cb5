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

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"

layout(push_constant, std430) uniform RomaVoxelizePushBlock { roma_voxelize_push pc; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVoxPositions { vec4 p[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaVoxIndices { uint i[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaVoxWords { uint w[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVoxParams {
    roma_grid_params grid;
};
layout(buffer_reference, std430, buffer_reference_align = 16) buffer RomaVoxQueue {
    roma_voxelize_queue header;
    uvec2 items[];       // (triangle, tile index)
};

// Same sine threshold as the raster path: below it a triangle has no area.
const float ROMA_VOX_DEGENERATE_SIN2 = 1e-12;
// Upper face of a cell: the largest float below 1 (half-open cells).
const float ROMA_VOX_BOX = 0.99999994;

struct roma_vox_triangle {
    vec3 g0, g1, g2;      // corners in grid units
    vec3 n;               // unnormalised normal
    ivec3 clo, chi;       // candidate cells (bounding box clamped to the grid)
    uint a, u, v;         // dominant axis and the two column axes (cyclic)
    bool keep;            // non-degenerate and touching the grid
};

roma_vox_triangle roma_vox_load(uint tri, int res)
{
    roma_grid_params grid = RomaVoxParams(pc.params).grid;
    RomaVoxIndices idx = RomaVoxIndices(pc.indices);
    RomaVoxPositions pos = RomaVoxPositions(pc.positions);
    roma_vox_triangle t;
    // Same expression as the raster path and the CPU voxelizer.
    precise vec3 g0 = (pos.p[idx.i[3u * tri + 0u]].xyz - grid.origin.xyz) * grid.inv_cell.x;
    precise vec3 g1 = (pos.p[idx.i[3u * tri + 1u]].xyz - grid.origin.xyz) * grid.inv_cell.x;
    precise vec3 g2 = (pos.p[idx.i[3u * tri + 2u]].xyz - grid.origin.xyz) * grid.inv_cell.x;
    t.g0 = g0;
    t.g1 = g1;
    t.g2 = g2;
    vec3 e1 = g1 - g0, e2 = g2 - g0;
    t.n = cross(e1, e2);
    // "keep if", so that NaN or Inf corners drop the triangle.
    t.keep = dot(t.n, t.n) > ROMA_VOX_DEGENERATE_SIN2 * dot(e1, e1) * dot(e2, e2);
    vec3 lo = min(g0, min(g1, g2)), hi = max(g0, max(g1, g2));
    t.keep = t.keep && all(greaterThanEqual(hi, vec3(0.0))) && all(lessThan(lo, vec3(float(res))));
    // Clamp in float before converting: no overflow for corners far outside.
    t.clo = ivec3(clamp(floor(lo), vec3(0.0), vec3(float(res - 1))));
    t.chi = ivec3(clamp(floor(hi), vec3(0.0), vec3(float(res - 1))));
    vec3 an = abs(t.n);
    t.a = (an.x >= an.y && an.x >= an.z) ? 0u : (an.y >= an.z ? 1u : 2u);
    t.u = (t.a + 1u) % 3u;
    t.v = (t.a + 2u) % 3u;
    return t;
}

// Columns of the triangle's footprint along its dominant axis.
uvec2 roma_vox_columns(roma_vox_triangle t)
{
    return uvec2(t.chi[t.u] - t.clo[t.u] + 1, t.chi[t.v] - t.clo[t.v] + 1);
}

// True when the projections of the triangle and of the box [0, s]^3 on axis are disjoint.
bool roma_vox_separated(vec3 axis, vec3 a, vec3 b, vec3 c)
{
    float p0 = dot(axis, a), p1 = dot(axis, b), p2 = dot(axis, c);
    float lo = min(p0, min(p1, p2)), hi = max(p0, max(p1, p2));
    vec3 s = axis * ROMA_VOX_BOX;
    float box_lo = min(s.x, 0.0) + min(s.y, 0.0) + min(s.z, 0.0);
    float box_hi = max(s.x, 0.0) + max(s.y, 0.0) + max(s.z, 0.0);
    return lo > box_hi || hi < box_lo;
}

// Separating-axis test of the triangle against cell c (coordinates relative to its corner).
bool roma_vox_overlaps(roma_vox_triangle t, ivec3 cell)
{
    vec3 o = vec3(cell);
    vec3 a = t.g0 - o, b = t.g1 - o, c = t.g2 - o;
    vec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
    if (any(greaterThan(lo, vec3(ROMA_VOX_BOX))) || any(lessThan(hi, vec3(0.0))))
        return false;
    vec3 e0 = b - a, e1 = c - b, e2 = a - c;
    if (roma_vox_separated(cross(e0, e1), a, b, c))
        return false;
    // Box axis x edge, written out (cross(unit_i, e)).
    if (roma_vox_separated(vec3(0.0, -e0.z, e0.y), a, b, c) ||
        roma_vox_separated(vec3(0.0, -e1.z, e1.y), a, b, c) ||
        roma_vox_separated(vec3(0.0, -e2.z, e2.y), a, b, c) ||
        roma_vox_separated(vec3(e0.z, 0.0, -e0.x), a, b, c) ||
        roma_vox_separated(vec3(e1.z, 0.0, -e1.x), a, b, c) ||
        roma_vox_separated(vec3(e2.z, 0.0, -e2.x), a, b, c) ||
        roma_vox_separated(vec3(-e0.y, e0.x, 0.0), a, b, c) ||
        roma_vox_separated(vec3(-e1.y, e1.x, 0.0), a, b, c) ||
        roma_vox_separated(vec3(-e2.y, e2.x, 0.0), a, b, c))
        return false;
    return true;
}

// Tests the cells of column (iu, iv) that the triangle's plane can reach and marks
// the overlapped ones.
void roma_vox_column(roma_vox_triangle t, int iu, int iv, int res, uint words)
{
    RomaVoxWords bom = RomaVoxWords(pc.bom);
    float na = t.n[t.a], nu = t.n[t.u], nv = t.n[t.v];
    float plane = dot(t.n, t.g0);
    // Plane depth at the column's four corners: the cells between (plus one either
    // side, for float error) are the only candidates.
    float d00 = (plane - nu * float(iu) - nv * float(iv)) / na;
    float d10 = (plane - nu * float(iu + 1) - nv * float(iv)) / na;
    float d01 = (plane - nu * float(iu) - nv * float(iv + 1)) / na;
    float d11 = (plane - nu * float(iu + 1) - nv * float(iv + 1)) / na;
    float dmin = min(min(d00, d10), min(d01, d11)), dmax = max(max(d00, d10), max(d01, d11));
    float lo_a = float(t.clo[t.a]), hi_a = float(t.chi[t.a]);
    int k0 = int(clamp(floor(dmin) - 1.0, lo_a, hi_a));
    int k1 = int(clamp(floor(dmax) + 1.0, lo_a, hi_a));
    if (!(dmin == dmin) || !(dmax == dmax)) {  // NaN: test the whole range
        k0 = t.clo[t.a];
        k1 = t.chi[t.a];
    }
    ivec3 cell;
    cell[t.u] = iu;
    cell[t.v] = iv;
    if (t.a == 2u) {
        // One texel: gather the bits per word, one atomic per word.
        uint base = (uint(iv) * uint(res) + uint(iu)) * words;
        uint mask = 0u;
        int word = k0 >> 5;
        for (int k = k0; k <= k1; ++k) {
            if ((k >> 5) != word) {
                if (mask != 0u)
                    atomicOr(bom.w[base + uint(word)], mask);
                mask = 0u;
                word = k >> 5;
            }
            cell.z = k;
            if (roma_vox_overlaps(t, cell))
                mask |= 1u << uint(k & 31);
        }
        if (mask != 0u)
            atomicOr(bom.w[base + uint(word)], mask);
    } else {
        for (int k = k0; k <= k1; ++k) {
            cell[t.a] = k;
            if (roma_vox_overlaps(t, cell))
                atomicOr(bom.w[(uint(cell.y) * uint(res) + uint(cell.x)) * words + uint(cell.z >> 5)],
                         1u << uint(cell.z & 31));
        }
    }
}

// Columns [u0, u1] x [v0, v1] of the footprint.
void roma_vox_columns_range(roma_vox_triangle t, int u0, int u1, int v0, int v1, int res, uint words)
{
    for (int iv = v0; iv <= v1; ++iv)
        for (int iu = u0; iu <= u1; ++iu)
            roma_vox_column(t, iu, iv, res, words);
}

// The columns of tile `tile` (row-major over ceil(columns / ROMA_VOXELIZE_TILE)).
void roma_vox_tile(roma_vox_triangle t, uint tile, int res, uint words)
{
    uvec2 cols = roma_vox_columns(t);
    uint tiles_u = (cols.x + ROMA_VOXELIZE_TILE - 1u) / ROMA_VOXELIZE_TILE;
    int u0 = t.clo[t.u] + int((tile % tiles_u) * ROMA_VOXELIZE_TILE);
    int v0 = t.clo[t.v] + int((tile / tiles_u) * ROMA_VOXELIZE_TILE);
    roma_vox_columns_range(t, u0, min(u0 + int(ROMA_VOXELIZE_TILE) - 1, t.chi[t.u]),
                           v0, min(v0 + int(ROMA_VOXELIZE_TILE) - 1, t.chi[t.v]), res, words);
}

#endif // ROMA_VOXELIZE_GLSL
