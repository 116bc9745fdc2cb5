// The NAADF baseline (src/study/naadf.h): the layout of its cells, the growth of an
// empty cell's box for its build passes, and the traversal for the passes that trace it.
#ifndef ROMA_NAADF_GLSL
#define ROMA_NAADF_GLSL

#include "roma_shared.h"

uint roma_naadf_index(ivec3 c, uint n) { return (uint(c.y) * n + uint(c.x)) * n + uint(c.z); }
ivec3 roma_naadf_cell(uint index, uint n) { return ivec3(int((index / n) % n), int(index / (n * n)), int(index % n)); }

// Where each layer starts in the buffer of words, for a grid of res cells a side.
uint roma_naadf_block_base(uint res)
{
    uint chunks = res / 16u;
    return chunks * chunks * chunks;
}
uint roma_naadf_voxel_base(uint res)
{
    uint blocks = res / 4u;
    return roma_naadf_block_base(res) + blocks * blocks * blocks;
}
uint roma_naadf_rows_base(uint res) { return roma_naadf_voxel_base(res) + res * res * (res / 2u); }

// A box's extent from its cell, `bits` a direction from bit `shift`: +x, -x, +y, -y, +z, -z.
uint roma_naadf_pack(ivec3 pos, ivec3 neg, uint bits, uint shift)
{
    uint w = 0u;
    for (int a = 0; a < 3; ++a) {
        ROMA_LOOP_TICK();
        w |= (uint(pos[a]) << (shift + uint(2 * a) * bits)) | (uint(neg[a]) << (shift + uint(2 * a + 1) * bits));
    }
    return w;
}
void roma_naadf_unpack(uint w, uint bits, uint shift, out ivec3 pos, out ivec3 neg)
{
    uint mask = (1u << bits) - 1u;
    for (int a = 0; a < 3; ++a) {
        ROMA_LOOP_TICK();
        pos[a] = int((w >> (shift + uint(2 * a) * bits)) & mask);
        neg[a] = int((w >> (shift + uint(2 * a + 1) * bits)) & mask);
    }
}

#if defined(ROMA_NAADF_BUILD_BLOCK)
// A domain of 4^3 cells (a block's voxels, a chunk's blocks) as 64 bits, cell (x, y, z) at
// bit (y * 4 + x) * 4 + z. A box is the intersection of three masks (its x, y and z ranges),
// kept as it grows, so testing a slice is a few operations.
uvec2 roma_naadf_axis_mask(int axis, int k) // the cells whose coordinate on axis is k
{
    if (axis == 0)
        return uvec2((15u << uint(4 * k)) * 0x10001u);
    if (axis == 2)
        return uvec2((1u << uint(k)) * 0x11111111u);
    return k < 2 ? uvec2(0xffffu << uint(16 * k), 0u) : uvec2(0u, 0xffffu << uint(16 * k - 32));
}

// The empty box around the empty cell c of `occupied`: grown one slice at a time, +x, -x,
// +y, -y, +z, -z in turn while the slice is empty and within the domain (the paper's
// expansion; the axis order decides between boxes of equal merit).
void roma_naadf_grow_block(uvec2 occupied, ivec3 c, out ivec3 pos, out ivec3 neg)
{
    ivec3 lo = c, hi = c;
    uvec2 range[3] = uvec2[3](roma_naadf_axis_mask(0, c.x), roma_naadf_axis_mask(1, c.y), roma_naadf_axis_mask(2, c.z));
    for (bool grew = true; grew;) {
        ROMA_LOOP_TICK();
        grew = false;
        for (int a = 0; a < 3; ++a) {
            ROMA_LOOP_TICK();
            for (int s = 0; s < 2; ++s) {
                ROMA_LOOP_TICK();
                int k = s == 0 ? hi[a] + 1 : lo[a] - 1;
                uvec2 slice = k >= 0 && k <= 3 ? roma_naadf_axis_mask(a, k) : uvec2(0u);
                if (slice != uvec2(0u) && (occupied & slice & range[(a + 1) % 3] & range[(a + 2) % 3]) == uvec2(0u)) {
                    range[a] |= slice;
                    hi[a] = max(hi[a], k);
                    lo[a] = min(lo[a], k);
                    grew = true;
                }
            }
        }
    }
    pos = hi - c;
    neg = c - lo;
}
#elif defined(ROMA_NAADF_BUILD_ROWS)
// A domain of up to 32^3 cells (the grid's chunks) as rows along z, given by the including
// pass: bit z of the row (x, y).
uint roma_naadf_row(int x, int y);

// True when no cell of the box lo..hi with coordinate k on `axis` (instead of its own) is
// occupied: one row per (x, y), z as a mask of the row.
bool roma_naadf_slice_empty(int axis, int k, ivec3 lo, ivec3 hi)
{
    lo[axis] = k;
    hi[axis] = k;
    uint zmask = ((2u << uint(hi.z)) - 1u) & ~((1u << uint(lo.z)) - 1u); // 2u << 31 wraps to 0: all bits
    for (int y = lo.y; y <= hi.y; ++y) {
        ROMA_LOOP_TICK();
        for (int x = lo.x; x <= hi.x; ++x) {
            ROMA_LOOP_TICK();
            if ((roma_naadf_row(x, y) & zmask) != 0u)
                return false;
        }
    }
    return true;
}

// The same growth over such a domain, within bmin..bmax and at most maxd cells from c in
// each direction.
void roma_naadf_grow(ivec3 c, ivec3 bmin, ivec3 bmax, int maxd, out ivec3 pos, out ivec3 neg)
{
    ivec3 lo = c, hi = c;
    for (bool grew = true; grew;) {
        ROMA_LOOP_TICK();
        grew = false;
        for (int a = 0; a < 3; ++a) {
            ROMA_LOOP_TICK();
            if (hi[a] < bmax[a] && hi[a] - c[a] < maxd && roma_naadf_slice_empty(a, hi[a] + 1, lo, hi)) {
                hi[a] += 1;
                grew = true;
            }
            if (lo[a] > bmin[a] && c[a] - lo[a] < maxd && roma_naadf_slice_empty(a, lo[a] - 1, lo, hi)) {
                lo[a] -= 1;
                grew = true;
            }
        }
    }
    pos = hi - c;
    neg = c - lo;
}
#endif

#ifdef ROMA_NAADF_WORD
// The empty box, in voxels (inclusive), of the cell cc of a layer whose cells are `size`
// voxels a side, from its word.
void roma_naadf_box(ivec3 cc, int size, uint w, uint bits, uint shift, out ivec3 lo, out ivec3 hi)
{
    ivec3 pos, neg;
    roma_naadf_unpack(w, bits, shift, pos, neg);
    lo = (cc - neg) * size;
    hi = (cc + pos + 1) * size - 1;
}

// True when origin + normalize(dir) * [0, tmax] (world units; +INF: to the grid's edge)
// enters an occupied voxel: the traversal of the paper (its section 3.4). From the chunk
// that holds the ray's point down to the first layer that is not mixed: a full cell is a
// hit, an empty one's box is left in one step, to the face the ray leaves it by; the cell
// beyond that face is the next. The same voxels and the same answer as the exact walk of
// the BOM (roma_bom_walk) but for rays through an edge or corner of a cell, where either
// may take the other side. ROMA_NAADF_WORD(i): word i of the cells.
bool roma_naadf_occluded(roma_grid_params grid, vec3 origin, vec3 dir, float tmax)
{
    int res = int(grid.dims.x);
    uint ures = uint(res);
    vec3 g = (origin - grid.origin.xyz) * grid.inv_cell.x;
    vec3 d = normalize(dir);
    bvec3 moving = notEqual(d, vec3(0.0));
    vec3 inv = vec3(moving.x ? 1.0 / d.x : 0.0, moving.y ? 1.0 / d.y : 0.0, moving.z ? 1.0 / d.z : 0.0);
    // The part of the ray inside the grid [0, RES]^3 and within tmax.
    float t = 0.0, tend = tmax * grid.inv_cell.x;
    for (int a = 0; a < 3; ++a) {
        ROMA_LOOP_TICK();
        if (!moving[a]) {
            if (g[a] < 0.0 || g[a] >= float(res))
                return false;
            continue;
        }
        float ta = -g[a] * inv[a], tb = (float(res) - g[a]) * inv[a];
        t = max(t, min(ta, tb));
        tend = min(tend, max(ta, tb));
    }
    if (t > tend)
        return false;
    ivec3 cell = clamp(ivec3(floor(g + d * t)), ivec3(0), ivec3(res - 1));
    uint block_base = roma_naadf_block_base(ures), voxel_base = roma_naadf_voxel_base(ures);
    // Each step leaves a box for the cell beyond one of its faces: at most the cells an
    // exact walk visits.
    for (int i = 0; i < 3 * res + 2; ++i) {
        ROMA_LOOP_TICK();
        ivec3 lo, hi;
        uint w = ROMA_NAADF_WORD(roma_naadf_index(cell >> 4, ures >> 4));
        if ((w & 3u) == ROMA_NAADF_FULL)
            return true;
        if ((w & 3u) == ROMA_NAADF_EMPTY) {
            roma_naadf_box(cell >> 4, 16, w, 5u, 2u, lo, hi);
        } else {
            w = ROMA_NAADF_WORD(block_base + roma_naadf_index(cell >> 2, ures >> 2));
            if ((w & 3u) == ROMA_NAADF_FULL)
                return true;
            if ((w & 3u) == ROMA_NAADF_EMPTY) {
                roma_naadf_box(cell >> 2, 4, w, 2u, 2u, lo, hi);
            } else {
                uint v = roma_naadf_index(cell, ures);
                w = ROMA_NAADF_WORD(voxel_base + (v >> 1)) >> ((v & 1u) * 16u);
                if ((w & 1u) != 0u)
                    return true;
                roma_naadf_box(cell, 1, w, 2u, 1u, lo, hi);
            }
        }
        // The face of the box the ray leaves it by (ties: x, then y, as the exact walk).
        vec3 face = mix(vec3(lo), vec3(hi + 1), greaterThan(d, vec3(0.0)));
        vec3 tf = (face - g) * inv;
        tf = vec3(moving.x ? tf.x : 1.0 / 0.0, moving.y ? tf.y : 1.0 / 0.0, moving.z ? tf.z : 1.0 / 0.0);
        float texit = min(tf.x, min(tf.y, tf.z));
        if (texit > tend)
            return false;
        int axis = tf.x == texit ? 0 : (tf.y == texit ? 1 : 2);
        ivec3 next = clamp(ivec3(floor(g + d * texit)), lo, hi);
        next[axis] = d[axis] > 0.0 ? hi[axis] + 1 : lo[axis] - 1;
        if (next[axis] < 0 || next[axis] >= res)
            return false; // out of the grid for good: it is convex
        cell = next;
    }
    return false;
}
#endif

#endif // ROMA_NAADF_GLSL
