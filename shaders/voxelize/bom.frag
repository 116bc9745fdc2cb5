#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// BOM rasterization, fragment stage: marks with atomicOr every cell of the
// fragment's column (along the projection axis) that the triangle overlaps
// inside the pixel square.
//
// The depth range is that of (triangle clipped to the pixel square), exactly:
// depth is linear, so its extremes lie on the clipped polygon's corners, which
// are edge/square-boundary crossings (Liang-Barsky) and square corners inside
// the triangle. The simpler plane-over-the-pixel range d +- 0.5 fwidth(d) is a
// superset that, for triangles steep along the axis, clamps to the triangle's
// whole depth extent and marks cells far from the surface.
#include "roma_bom.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaBomWords { uint w[]; };

layout(location = 0) flat in vec3 v_tri0;
layout(location = 1) flat in vec3 v_tri1;
layout(location = 2) flat in vec3 v_tri2;
layout(location = 3) noperspective in float v_depth;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// Widens range (x = min, y = max) by the depths of segment a-b inside the pixel
// square [lo, hi]^2.
void clip_edge(vec3 a, vec3 b, vec2 lo, vec2 hi, inout vec2 range)
{
    vec2 dir = b.xy - a.xy;
    float t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 2; ++k) {
        ROMA_LOOP_TICK();
        if (abs(dir[k]) < 1e-20) {
            if (a[k] < lo[k] || a[k] > hi[k])
                return;
        } else {
            float ta = (lo[k] - a[k]) / dir[k];
            float tb = (hi[k] - a[k]) / dir[k];
            t0 = max(t0, min(ta, tb));
            t1 = min(t1, max(ta, tb));
        }
    }
    if (t0 > t1)
        return;
    float d0 = mix(a.z, b.z, t0), d1 = mix(a.z, b.z, t1);
    range = vec2(min(range.x, min(d0, d1)), max(range.y, max(d0, d1)));
}

void main()
{
    roma_grid_params grid = RomaBomParams(pc.params).grid;
    int res = int(grid.dims.x);
    uint words = grid.dims.y;
    uint axis = min(pc.config.x, 2u);
    ivec2 pix = ivec2(floor(gl_FragCoord.xy));
    if (any(lessThan(pix, ivec2(0))) || any(greaterThanEqual(pix, ivec2(res))))
        return;

    vec3 a = v_tri0, b = v_tri1, c = v_tri2;
    // Pixels are half-open like the cells ([k, k+1): a point on a pixel's upper face
    // belongs to the next one): the upper face is the largest float below k + 1.
    vec2 lo = vec2(pix);
    vec2 hi = uintBitsToFloat(floatBitsToUint(lo + 1.0) - 1u);
    vec2 range = vec2(3.0e38, -3.0e38);
    clip_edge(a, b, lo, hi, range);
    clip_edge(b, c, lo, hi, range);
    clip_edge(c, a, lo, hi, range);
    // Square corners inside the triangle: one edge function per edge, each relative
    // to its own edge's start, so that axis-aligned edges (walls on cell faces) get
    // exact signs. On an edge counts as inside: extra cells are preferred to misses.
    float area = cross2(b.xy - a.xy, c.xy - a.xy);
    if (abs(area) > 1e-30) {
        float s = area > 0.0 ? 1.0 : -1.0;
        for (int k = 0; k < 4; ++k) {
            ROMA_LOOP_TICK();
            vec2 q = vec2((k & 1) != 0 ? hi.x : lo.x, (k & 2) != 0 ? hi.y : lo.y);
            float wc = s * cross2(b.xy - a.xy, q - a.xy);  // weight of c
            float wa = s * cross2(c.xy - b.xy, q - b.xy);
            float wb = s * cross2(a.xy - c.xy, q - c.xy);
            if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) {
                float d = (wa * a.z + wb * b.z + wc * c.z) / max(wa + wb + wc, 1e-30);
                range = vec2(min(range.x, d), max(range.y, d));
            }
        }
    }
    float tmin = min(a.z, min(b.z, c.z)), tmax = max(a.z, max(b.z, c.z));
    // The rasterizer (fixed-point) and the test above (float) can disagree at the
    // triangle's rim: fall back to the depth at the pixel centre.
    if (!(range.x <= range.y)) {
        if ((pc.config.w & ROMA_BOM_FLAG_CONSERVATIVE) != 0u)
            return;  // grown triangle: this pixel does not touch the real one
        range = vec2(v_depth);
    }
    range = clamp(range, tmin, tmax);
    if (range.y < 0.0 || range.x >= float(res))
        return;  // the triangle crosses this column outside the grid
    int c0 = int(floor(max(range.x, 0.0)));
    int c1 = int(floor(min(range.y, float(res - 1))));  // clamp before int(): no overflow

    RomaBomWords bom = RomaBomWords(pc.bom);
    if (axis == 2u) {
        // Cells (u, v, c0..c1): consecutive bits of texel (u, v), one atomic per word.
        uint base = (uint(pix.y) * uint(res) + uint(pix.x)) * words;
        for (int w = c0 >> 5; w <= (c1 >> 5); ++w) {
            ROMA_LOOP_TICK();
            uint first = uint(max(c0 - 32 * w, 0));
            uint last = uint(min(c1 - 32 * w, 31));
            // Shifts stay in 0..31 (a shift by 32 is undefined).
            uint mask = (0xffffffffu >> (31u - last)) & (0xffffffffu << first);
            atomicOr(bom.w[base + uint(w)], mask);
        }
    } else if (axis == 0u) {
        // (u, v) = (y, z), depth = x: cell (c, u, v).
        uint bit = 1u << (uint(pix.y) & 31u);
        for (int x = c0; x <= c1; ++x) {
            ROMA_LOOP_TICK();
            atomicOr(bom.w[(uint(pix.x) * uint(res) + uint(x)) * words + (uint(pix.y) >> 5)], bit);
        }
    } else {
        // (u, v) = (z, x), depth = y: cell (v, c, u).
        uint bit = 1u << (uint(pix.x) & 31u);
        for (int y = c0; y <= c1; ++y) {
            ROMA_LOOP_TICK();
            atomicOr(bom.w[(uint(y) * uint(res) + uint(pix.y)) * words + (uint(pix.x) >> 5)], bit);
        }
    }
}
