#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Distance field, step 1 of 3: one invocation per cell; an occupied BOM cell is its own
// seed, an empty one has none yet.
#include "roma_distance_field.glsl"

layout(local_size_x = ROMA_DF_WORKGROUP_SIZE) in;
layout(std430, binding = ROMA_DF_BINDING_BOM) readonly buffer Bom { uint bom[]; };
layout(std430, binding = ROMA_DF_BINDING_SEEDS_OUT) writeonly buffer SeedsOut { uint seeds_out[]; };
layout(push_constant) uniform Push { roma_df_push pc; };

void main()
{
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_DF_WORKGROUP_SIZE + gl_LocalInvocationID.x;
    if (i >= pc.config.z)
        return;
    // Cell index (y * RES + x) * RES + z is bit z % 32 of the texel's word z / 32.
    bool occupied = (bom[i >> 5] & (1u << (i & 31u))) != 0u;
    seeds_out[i] = occupied ? roma_df_pack(roma_df_cell(i, pc.config.x)) : ROMA_DF_NO_SEED;
}
