#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "roma_loop_guard.glsl"
// Direct light from point, spot and directional lights: per pixel and light,
// one un-snapped shadow ray through the ROMA maps; the irradiance is added to
// accum so that frames (new jitter each) average out the voxelization.
#include "roma_bound_bom.glsl"
#include "roma_lights.glsl"
#include "roma_pixel_bindings.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(std430, set = ROMA_TRACE_SET, binding = ROMA_PIXEL_BINDING_ACCUM) buffer RomaPassAccum { vec4 accum[]; };

layout(push_constant) uniform Push { roma_punctual_push pc; };

void main()
{
    uint width = pc.config.x, height = pc.config.y, light_count = pc.config.z, max_steps = pc.config.w;
    uint pixel;
    if (!roma_bound_pixel(pixel))
        return;
    roma_gbuffer_pixel g = roma_gbuffer_fetch(pixel);
    if (roma_is_inf(g.position_t.w))
        return;
    vec3 p = g.position_t.xyz, n = g.shading_normal.xyz, ng = g.geometric_normal.xyz;
    float offset = pc.ray.x;
    vec3 origin = p + ng * offset;
    roma_use_ray_start(pc.bom);
    roma_shadow_exact = pc.ray.z > 0.0;
    vec3 E = vec3(0.0);
    for (uint i = pc.part.x; i < min(pc.part.y, light_count); ++i) { // this dispatch's part
        ROMA_LOOP_TICK();
        E += roma_punctual_irradiance(RomaLights(pc.lights).l[i], p, ng, n, origin, offset, pc.ray.y, max_steps);
    }
    accum[pixel] += vec4(E, 0.0);
}
