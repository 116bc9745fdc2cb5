#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Rotation by gathering (paper Algorithm 1): one invocation writes one 32-bit word of
// one ray-aligned map by sampling the BOM at its cells' sample points. The fallback
// when the occupied-cell list overflows (dispatched indirectly), and the definition
// the C mirror and the scatter path reproduce.
#include "roma_rotate.glsl"

layout(local_size_x = ROMA_ROTATE_WORKGROUP_SIZE) in;

void main()
{
    roma_grid_params grid = roma_rotate_grid();
    uint res = grid.dims.x, words = grid.dims.y, map_count = grid.dims.w, bom_base = roma_rotate_bom_base(grid);
    // 2D dispatch: more than 65535 groups are needed at RES 256 or A >= 8.
    uint id = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_ROTATE_WORKGROUP_SIZE
              + gl_LocalInvocationID.x;
    uint per_map = res * res * words;
    if (id >= per_map * map_count)
        return;
    uint k = id / per_map, r = id - k * per_map;
    uint texel = r / words, w = r - texel * words;
    uint x = texel % res, y = texel / res;
    roma_map_frame f = frames[grid.level.z + k];
    float fres = float(res);
    uint out_word = 0u;
    for (uint i = 0u; i < 32u; ++i) {
        ROMA_LOOP_TICK();
        // Two samples per cell along the map's z, a quarter cell either side of the centre:
        // rotated cells are up to sqrt(3) BOM cells long, and one sample per cell would step
        // over one-cell-thick walls.
        for (uint h = 0u; h < ROMA_ROTATE_SAMPLES; ++h) {
            ROMA_LOOP_TICK();
            vec3 b = roma_rotate_sample(f, x, y, w * 32u + i, h);
            if (b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0 && b.x < fres && b.y < fres && b.z < fres) {
                uvec3 c = uvec3(floor(b));
                uint word = bom[bom_base + (c.y * res + c.x) * words + (c.z >> 5)];
                out_word |= ((word >> (c.z & 31u)) & 1u) << i;
            }
        }
    }
    maps[grid.level.w + id] = out_word;
}
