#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// The trace ladder (roma-bench, src/study/trace_ladder.c): the batch trace by address cut after
// each of its steps, so that the time of every step shows as the difference to the rung below.
// LADDER_STEP (a specialization constant): 0 launches the invocations and returns; 1 reads each
// ray and writes a hit; 2 also resolves the direction (normalise, map selection, fold); 3 also
// maps the origin and fetches the first map word of its column; 4 is the whole snapped any-hit
// trace (what trace.comp runs). Each rung writes something that depends on its work.
// The workgroup size is specialization constant 2 (the ladder sweeps it on the whole trace).
#define ROMA_BATCH_GROUP_SIZE_ID 2
#include "roma_batch_trace.glsl"

layout(constant_id = 1) const uint LADDER_STEP = 4u;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaRays { roma_ray r[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) writeonly buffer RomaHits { roma_hit h[]; };

void main()
{
    uint i;
    if (!roma_batch_index(i) || LADDER_STEP == 0u)
        return;
    roma_use_addresses(pc.params, pc.maps);
    roma_ray ray = RomaRays(pc.rays).r[i];
    roma_hit hit = roma_hit(ray.tmin, 0u);
    if (LADDER_STEP >= 2u && LADDER_STEP < 4u) {
        roma_grid_params grid = roma_fetch_grid(0u);
        roma_ray_dir d = roma_ray_dir_of(ray.dir, grid.dims.z);
        hit.info = d.k | (d.folded ? ROMA_HIT_FOLDED : 0u);
        if (LADDER_STEP == 3u && d.unit) {
            roma_map_frame f = roma_fetch_frame(grid.level.z + d.k);
            vec3 m = roma_to_map(grid, f, ray.origin);
            uint res = grid.dims.x;
            if (roma_all_finite(m) && m.x >= 0.0 && m.x < float(res) && m.y >= 0.0 && m.y < float(res))
                hit.info ^= roma_fetch_word(grid.level.w + roma_texel_base(d.k, uint(m.x), uint(m.y), res, grid.dims.y));
        }
    } else if (LADDER_STEP == 4u) {
        hit = roma_trace_snapped(ray.origin, ray.dir, ray.tmin, ray.tmax, false);
    }
    RomaHits(pc.hits).h[i] = hit;
}
