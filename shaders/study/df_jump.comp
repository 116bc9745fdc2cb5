#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Distance field, step 2 of 3: one jump-flooding pass (Rong and Tan 2006) at step k. Each
// cell keeps the nearest of its own seed and the seeds of the 26 cells k away.
#include "roma_distance_field.glsl"

layout(local_size_x = ROMA_DF_WORKGROUP_SIZE) in;
layout(std430, binding = ROMA_DF_BINDING_SEEDS_IN) readonly buffer SeedsIn { uint seeds_in[]; };
layout(std430, binding = ROMA_DF_BINDING_SEEDS_OUT) writeonly buffer SeedsOut { uint seeds_out[]; };
layout(push_constant) uniform Push { roma_df_push pc; };

void main()
{
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_DF_WORKGROUP_SIZE + gl_LocalInvocationID.x;
    if (i >= pc.config.z)
        return;
    uint res = pc.config.x;
    int k = int(pc.config.y);
    ivec3 p = roma_df_cell(i, res);
    uint best = seeds_in[i];
    int best_d2 = 0x7fffffff;
    if (best != ROMA_DF_NO_SEED) {
        ivec3 e = roma_df_unpack(best) - p;
        best_d2 = e.x * e.x + e.y * e.y + e.z * e.z;
    }
    for (int dy = -1; dy <= 1; ++dy) {
        ROMA_LOOP_TICK();
        for (int dx = -1; dx <= 1; ++dx) {
            ROMA_LOOP_TICK();
            for (int dz = -1; dz <= 1; ++dz) {
                ROMA_LOOP_TICK();
                ivec3 q = p + k * ivec3(dx, dy, dz);
                if ((dx | dy | dz) == 0 || any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, ivec3(res))))
                    continue;
                uint s = seeds_in[roma_df_index(q, res)];
                if (s == ROMA_DF_NO_SEED)
                    continue;
                ivec3 e = roma_df_unpack(s) - p;
                int d2 = e.x * e.x + e.y * e.y + e.z * e.z;
                // Ties go to the lower packed seed, so the result does not depend on the order.
                if (d2 < best_d2 || (d2 == best_d2 && s < best)) {
                    best_d2 = d2;
                    best = s;
                }
            }
        }
    }
    seeds_out[i] = best;
}
