#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Shadowed irradiance from punctual lights on an engine's G-buffer images
// (roma_light_effect): per pixel and light one un-snapped shadow ray through the map bound
// at set 0; formulas as passes/punctual_lights.comp and the reference tracer.
#define ROMA_TRACE_SET 0
#include "roma_lights.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform sampler2D roma_light_position;
layout(set = 1, binding = 1) uniform sampler2D roma_light_normal;
layout(set = 1, binding = 2) uniform sampler2D roma_light_geometric_normal;
layout(set = 1, binding = 3, rgba32f) uniform writeonly image2D roma_light_output;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaLights { roma_gpu_light l[]; };

layout(push_constant) uniform Push { roma_punctual_push pc; };

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    uint width = pc.config.x, height = pc.config.y, light_count = pc.config.z, max_steps = pc.config.w;
    if (xy.x >= width || xy.y >= height)
        return;
    ivec2 at = ivec2(xy);
    vec4 position = texelFetch(roma_light_position, at, 0);
    if (!(position.w > 0.0)) {
        imageStore(roma_light_output, at, vec4(0.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = normalize(texelFetch(roma_light_normal, at, 0).xyz);
    vec3 ng = normalize(texelFetch(roma_light_geometric_normal, at, 0).xyz);
    float offset = pc.ray.x;
    vec3 origin = p + ng * offset;
    vec3 E = vec3(0.0);
    for (uint i = 0u; i < light_count; ++i) {
        roma_gpu_light light = RomaLights(pc.lights).l[i];
        vec3 l;
        float f = roma_punctual_factor(light, p, ng, n, l);
        if (f == 0.0)
            continue;
        bool visible;
        if (uint(light.position_type.w) == ROMA_GPU_LIGHT_DIRECTIONAL) {
            roma_hit h = roma_trace_unsnapped(origin, l, pc.ray.y, 1.0 / 0.0, false, max_steps);
            visible = (h.info & ROMA_HIT_FLAG) == 0u;
        } else {
            visible = roma_segment_visible(origin, light.position_type.xyz, offset, pc.ray.y, max_steps);
        }
        if (visible)
            E += roma_bounded_irradiance(f, light.color_intensity.rgb);
    }
    imageStore(roma_light_output, at, vec4(E, 0.0));
}
