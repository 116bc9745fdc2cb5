#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Ambient occlusion from the G-buffer: one invocation per covered pixel (indirect
// dispatch over the pixel list), spp snapped any-hit rays through the ROMA maps; adds the
// unoccluded count to accum so that frames accumulate (the caller clears it before
// frame 0). Every buffer is bound (set 0: the trace set's two bindings, then these).
#include "roma_bound_bom.glsl"
#include "roma_pixel_bindings.glsl"
#include "roma/ray_start.glsl"
#include "roma_sampling.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaAoAccum { uint accum[]; };

layout(push_constant) uniform Push { roma_ao_push pc; };

// What the rays trace (roma_ao_method, src/passes/ao.h): 0 the ROMA maps; the accuracy
// study's baselines 1 the BOM, each ray walked exactly from the origin to its end (no
// snapping, no rotation: the voxelization's own error apart from ROMA's), 2 the distance
// field built from the BOM, bound in its place, sphere-traced, 3 the G-buffer's depth
// (screen space, no map), 4 the NAADF hierarchy built from the BOM, bound in its place (the
// voxels of 1, empty space left a box at a time). A constant, so that ROMA's pass carries
// none of their code.
layout(constant_id = 0) const uint ROMA_AO_METHOD = 0u;

#define ROMA_DF_WORD(i) roma_fetch_bom_word(i)
#include "roma_distance_field.glsl"
#include "roma_ssao.glsl"
#define ROMA_NAADF_WORD(i) roma_fetch_bom_word(i)
#include "roma_naadf.glsl"

void main()
{
    uint spp = pc.config.z, frame = pc.config.w;
    uint pixel;
    if (!roma_bound_pixel(pixel))
        return;
    roma_gbuffer_pixel g = roma_gbuffer_fetch(pixel);
    vec3 n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    precise vec3 origin = g.position_t.xyz + ng * pc.ray.x;
    roma_use_ray_start(pc.bom);
    roma_grid_params grid = roma_fetch_grid(0u); // the baselines' grid (one level)
    uint seed = pc.config2.x, open = 0u;
    for (uint k = pc.sample_first; k < min(pc.sample_end, spp); ++k) { // this dispatch's part
        ROMA_LOOP_TICK();
        uint s = frame * spp + k; // new directions every frame, as in the reference
        vec3 local_dir = roma_cosine_hemisphere(roma_random(seed, pixel, s, 0u), roma_random(seed, pixel, s, 1u));
        vec3 dir = roma_local_to_world(n, local_dir);
        // Below the geometric surface counts as occluded, as in the reference.
        precise float below = dir.x * ng.x + dir.y * ng.y + dir.z * ng.z;
        if (below <= 0.0)
            continue;
        if (ROMA_AO_METHOD == 1u) {
            open += roma_bom_walk(origin, dir, pc.ray.y, 1 << 20) < 0.0 ? 1u : 0u;
            continue;
        }
        if (ROMA_AO_METHOD == 2u) {
            open += roma_df_occluded(grid, origin, dir, pc.ray.y, pc.config2.y, pc.ray.w) ? 0u : 1u;
            continue;
        }
        if (ROMA_AO_METHOD == 4u) {
            open += roma_naadf_occluded(grid, origin, dir, pc.ray.y) ? 0u : 1u;
            continue;
        }
        if (ROMA_AO_METHOD == 3u) {
            open += roma_ssao_blocked(origin, dir, pc.ray.z, pc.ray.y) ? 0u : 1u;
            continue;
        }
        // The skipped start, walked exactly: no ray passes a wall it starts next to.
        if (roma_ray_start_blocked(origin, dir, min(pc.ray.z, pc.ray.y)))
            continue;
        roma_hit h = roma_trace_snapped(origin, dir, pc.ray.z, pc.ray.y, false);
        open += (h.info & ROMA_HIT_FLAG) == 0u ? 1u : 0u;
    }
    if (open != 0u)
        accum[pixel] += open;
}
