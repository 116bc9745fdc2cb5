#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Rotation by scattering: one invocation per (occupied BOM cell, map). It finds the
// sample points of the map whose BOM coordinates can fall in its cell (the cell's
// bounding box in map coordinates, padded against float error), evaluates each with the
// gather's own expression and sets the map bit when it lands in the cell. The union over
// the occupied cells is exactly the gather's result; the work follows the occupied
// cells (a few percent of the grid) instead of every map word.
#include "roma_rotate.glsl"

layout(local_size_x = ROMA_ROTATE_WORKGROUP_SIZE) in;

// Padding of the cell's box in map cells: far above the float error of the mapping
// (about 1e-5 cells at RES 256), so no sample whose BOM coordinates fall in the cell is
// left out; samples that do not are rejected by the exact test.
const float ROMA_SCATTER_PAD = 1.0 / 64.0;

// Every invocation of a workgroup works on the same map: its frame is loaded once.
shared roma_map_frame frame_shared;

void main()
{
    uint k = gl_WorkGroupID.y;

    uint count = list_header.scatter.w;
    uint item = gl_GlobalInvocationID.x;
    if (count > pc.config.x || item >= count)
        return;  // an overflowed list: the gather runs instead
    uint packed = cells[item];
    ivec3 c = ivec3(packed & 0xffu, (packed >> 8u) & 0xffu, packed >> 16u);
    roma_grid_params grid = roma_rotate_grid();
    uint res = grid.dims.x, words = grid.dims.y;
    roma_map_frame f = frames[grid.level.z + k];
    // BOM cell -> map coordinates: m = to_map . (b * cell) + to_map.w, in grid units.
    float cell = grid.origin.w * grid.inv_cell.y;
    vec3 centre = (vec3(c) + 0.5) * cell;
    vec3 rx = f.to_map_0.xyz, ry = f.to_map_1.xyz, rz = f.to_map_2.xyz;
    vec3 m = vec3(dot(rx, centre) + f.to_map_0.w, dot(ry, centre) + f.to_map_1.w, dot(rz, centre) + f.to_map_2.w);
    vec3 half_extent = 0.5 * cell * vec3(dot(abs(rx), vec3(1.0)), dot(abs(ry), vec3(1.0)), dot(abs(rz), vec3(1.0)))
                       + ROMA_SCATTER_PAD;
    vec3 lo = m - half_extent, hi = m + half_extent;
    float fres = float(res);
    // Sample points: x + 0.5, y + 0.5 and j + (h + 0.5) / S along z.
    int x0 = int(clamp(ceil(lo.x - 0.5), 0.0, fres)), x1 = int(clamp(floor(hi.x - 0.5), -1.0, fres - 1.0));
    int y0 = int(clamp(ceil(lo.y - 0.5), 0.0, fres)), y1 = int(clamp(floor(hi.y - 0.5), -1.0, fres - 1.0));
    vec3 fc = vec3(c);
    vec3 m0 = f.map_to_bom_0.xyz, m1 = f.map_to_bom_1.xyz, m2 = f.map_to_bom_2.xyz, m3 = f.map_to_bom_3.xyz;
    for (int y = y0; y <= y1; ++y) {
        ROMA_LOOP_TICK();
        for (int x = x0; x <= x1; ++x) {
            ROMA_LOOP_TICK();
            // The column's line b(z) = p + m2 * z through the BOM: the z interval inside the
            // cell (slab test, padded); only its samples are evaluated exactly.
            vec3 p = (m0 * (float(x) + 0.5) + m1 * (float(y) + 0.5)) + m3;
            float zlo = 0.0, zhi = fres;
            for (int i = 0; i < 3; ++i) {
                ROMA_LOOP_TICK();
                if (abs(m2[i]) > 1e-6) {
                    float ta = (fc[i] - p[i]) / m2[i], tb = (fc[i] + 1.0 - p[i]) / m2[i];
                    zlo = max(zlo, min(ta, tb));
                    zhi = min(zhi, max(ta, tb));
                } else if (p[i] < fc[i] - ROMA_SCATTER_PAD || p[i] > fc[i] + 1.0 + ROMA_SCATTER_PAD) {
                    zhi = -1.0;
                }
            }
            zlo -= ROMA_SCATTER_PAD;
            zhi += ROMA_SCATTER_PAD;
            if (!(zlo <= zhi))
                continue;
            int ja = int(clamp(floor(zlo), 0.0, fres - 1.0)), jb = int(clamp(floor(zhi), 0.0, fres - 1.0));
            uint base = grid.level.w + ((k * res + uint(y)) * res + uint(x)) * words;
            uint mask = 0u;
            int word = ja >> 5;
            for (int j = ja; j <= jb; ++j) {
                ROMA_LOOP_TICK();
                if ((j >> 5) != word) {
                    if (mask != 0u)
                        atomicOr(maps[base + uint(word)], mask);
                    mask = 0u;
                    word = j >> 5;
                }
                bool hit = false;
                for (uint h = 0u; h < ROMA_ROTATE_SAMPLES; ++h) {
                    ROMA_LOOP_TICK();
                    float z = float(j) + (float(h) + 0.5) / float(ROMA_ROTATE_SAMPLES);
                    if (z >= zlo && z <= zhi)
                        hit = hit || all(equal(floor(roma_rotate_sample(f, uint(x), uint(y), uint(j), h)), fc));
                }
                if (hit)
                    mask |= 1u << uint(j & 31);
            }
            if (mask != 0u)
                atomicOr(maps[base + uint(word)], mask);
        }
    }
}
