#version 460
// The example engine's G-buffer for its AO pass: the room's floor seen from above, one
// pixel per floor patch (world position and normal), written as the engine's images.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D gbuffer_position;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D gbuffer_normal;

layout(push_constant) uniform Push {
    uvec2 size;
    vec2 pad;
    vec4 area; // x0, z0, x1, z1 of the floor
} pc;

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= pc.size.x || xy.y >= pc.size.y)
        return;
    vec2 uv = (vec2(xy) + 0.5) / vec2(pc.size);
    vec3 p = vec3(mix(pc.area.x, pc.area.z, uv.x), 0.0, mix(pc.area.y, pc.area.w, uv.y));
    imageStore(gbuffer_position, ivec2(xy), vec4(p, 1.0));
    imageStore(gbuffer_normal, ivec2(xy), vec4(0.0, 1.0, 0.0, 0.0));
}
