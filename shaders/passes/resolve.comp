#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// One frame's accumulated sums of a pass -> the effect's value per pixel, as
// the offline resolve computes it (src/passes/effect_render.c).
#include "roma_lights.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaU32s { uint u[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer RomaUvec2s { uvec2 u[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RomaVec4Out { vec4 v[]; };

layout(push_constant) uniform Push { roma_resolve_push pc; };

const float INV_PI = 0.31830988618379067;

bool has(uvec2 address) { return (address.x | address.y) != 0u; }

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    uint width = pc.config.x, height = pc.config.y, mode = pc.config.z;
    if (xy.x >= width || xy.y >= height)
        return;
    uint pixel = xy.y * width + xy.x;
    roma_gbuffer_pixel g = RomaGbufferPixels(pc.pixels).p[pixel];
    bool covered = !roma_is_inf(g.position_t.w);
    float inv_spp = pc.scale.x;
    vec3 value = vec3(mode == ROMA_RESOLVE_AO ? 1.0 : 0.0); // background: nothing occludes, nothing lit
    if (covered) {
        if (mode == ROMA_RESOLVE_AO) {
            value = vec3(float(RomaU32s(pc.a).u[pixel]) * inv_spp);
        } else if (mode == ROMA_RESOLVE_DIRECT) {
            vec3 E = has(pc.a) ? RomaVec4s(pc.a).v[pixel].rgb : vec3(0.0);
            if (has(pc.b))
                E += RomaVec4s(pc.b).v[pixel].rgb * inv_spp;
            value = g.albedo.rgb * INV_PI * E;
        } else if (mode == ROMA_RESOLVE_GI) {
            value = g.albedo.rgb * RomaVec4s(pc.a).v[pixel].rgb * inv_spp;
        } else {
            uvec2 c = RomaUvec2s(pc.a).u[pixel];
            value = vec3(c.y > 0u ? float(c.x) / float(c.y) * float(pc.config.w) : 0.0);
        }
    }
    RomaVec4Out(pc.dst).v[pixel] = vec4(value, 0.0);
}
