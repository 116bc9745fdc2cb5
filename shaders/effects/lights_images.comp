#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Shadowed irradiance from punctual lights and area lights on an engine's G-buffer images
// (roma_light_effect): per pixel and punctual light one un-snapped shadow ray through the
// map bound at set 0; per area-light sample one more, the samples drawn as the reference
// draws them (dimensions 2-4, pixel y * width + x, sample frame * samples + k); formulas as
// passes/punctual_lights.comp, passes/soft_shadows.comp and the reference tracer.
#define ROMA_TRACE_SET 0
// The map's BOM, bound after the images (image_effect.c), for the exact walk of the
// rays' start: bound loads are several times faster than loads by address on CPU devices.
#define ROMA_BOM_SET 1
#define ROMA_BOM_BINDING 4
#include "roma_bound_bom.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform sampler2D roma_light_position;
layout(set = 1, binding = 1) uniform sampler2D roma_light_normal;
layout(set = 1, binding = 2) uniform sampler2D roma_light_geometric_normal;
layout(set = 1, binding = 3, rgba32f) uniform writeonly image2D roma_light_output;


layout(push_constant) uniform Push { roma_light_images_push pc; };

const uint DIM_DIRECT_AREA = 2u;

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
    roma_use_ray_start(pc.bom);
    vec3 E = vec3(0.0);
    for (uint i = 0u; i < light_count; ++i)
        E += roma_punctual_irradiance(RomaLights(pc.lights).l[i], p, ng, n, origin, offset, pc.ray.y, max_steps);
    uint seed = pc.config2.x, emitter_count = pc.config2.y, samples = pc.config2.z, frame = pc.config2.w;
    if (emitter_count > 0u && samples > 0u) {
        uint pixel = xy.y * width + xy.x;
        vec3 area = vec3(0.0);
        for (uint k = 0u; k < samples; ++k) {
            uint s = frame * samples + k;
            vec3 u = vec3(roma_random(seed, pixel, s, DIM_DIRECT_AREA), roma_random(seed, pixel, s, DIM_DIRECT_AREA + 1u),
                          roma_random(seed, pixel, s, DIM_DIRECT_AREA + 2u));
            area += roma_area_sample_irradiance(RomaEmitters(pc.emitters), RomaFloats(pc.cdf), emitter_count, u, p, ng,
                                                n, origin, offset, pc.ray.y, max_steps);
        }
        E += area / float(samples);
    }
    imageStore(roma_light_output, at, vec4(E, 0.0));
}
