#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "roma_loop_guard.glsl"
// Lists the occupied BOM cells for the scatter rotation: one invocation per BOM word of the
// slot pc.source.x (the level's own BOM, or the dynamic instances' alone), words source.y ..
// source.y + source.z - 1 of it (all, or the rows a dynamic box covers).
// Grows the scatter's indirect dispatch; when the list is full, enables the gather.
#include "roma_rotate.glsl"

layout(local_size_x = ROMA_ROTATE_WORKGROUP_SIZE) in;

void main()
{
    roma_grid_params grid = roma_rotate_grid();
    uint res = grid.dims.x, words = grid.dims.y;
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * ROMA_ROTATE_WORKGROUP_SIZE
             + gl_LocalInvocationID.x;
    if (i >= pc.source.z)
        return;
    uint id = pc.source.y + i;
    uint word = bom[pc.source.x * res * res * words + id];
    if (word == 0u)
        return;
    uint n = uint(bitCount(word));
    uint capacity = pc.config.x;
    // One atomic per subgroup: the lanes' places follow from a prefix sum of their counts.
    uint total = subgroupAdd(n), before = subgroupExclusiveAdd(n), base = 0u;
    if (subgroupElect())
        base = atomicAdd(list_header.scatter.w, total);
    uint first = subgroupBroadcastFirst(base) + before;
    if (first + n > capacity) {
        // Overflow: the gather rebuilds every map (the scatter skips an incomplete list).
        atomicMax(list_header.gather.x, pc.config.y);
        atomicMax(list_header.gather.y, pc.config.z);
        return;
    }
    uint texel = id / words, w = id - texel * words;
    uint xy = (texel % res) | ((texel / res) << 8u);
    for (uint i = 0u; i < n; ++i) {
        ROMA_LOOP_TICK();
        int b = findLSB(word);
        word &= word - 1u;
        cells[first + i] = xy | ((w * 32u + uint(b)) << 16u);
    }
    atomicMax(list_header.scatter.x, (first + n + ROMA_ROTATE_WORKGROUP_SIZE - 1u) / ROMA_ROTATE_WORKGROUP_SIZE);
}
