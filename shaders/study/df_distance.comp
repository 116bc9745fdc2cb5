#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Distance field, step 3 of 3: one invocation per pair of cells along z writes their
// distances to their seeds, in cells, as two float16 (the storage of ROMA's maps at A 4,
// as in the ROMA paper's baseline). A grid with no occupied cell is far everywhere.
#include "roma_distance_field.glsl"

layout(local_size_x = ROMA_DF_WORKGROUP_SIZE) in;
layout(std430, binding = ROMA_DF_BINDING_SEEDS_IN) readonly buffer SeedsIn { uint seeds_in[]; };
layout(std430, binding = ROMA_DF_BINDING_DISTANCES) writeonly buffer Distances { uint distances[]; };
layout(push_constant) uniform Push { roma_df_push pc; };

float seed_distance(uint i)
{
    uint s = seeds_in[i];
    if (s == ROMA_DF_NO_SEED)
        return 65504.0; // the largest float16
    vec3 e = vec3(roma_df_unpack(s) - roma_df_cell(i, pc.config.x));
    return length(e);
}

void main()
{
    uint w = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_DF_WORKGROUP_SIZE + gl_LocalInvocationID.x;
    if (2u * w >= pc.config.z)
        return;
    distances[w] = packHalf2x16(vec2(seed_distance(2u * w), seed_distance(2u * w + 1u)));
}
