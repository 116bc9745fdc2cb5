// libroma: light evaluation shared by the light passes. Formulas follow the
// reference tracer (src/reference/estimators.c): KHR_lights_punctual units,
// glTF range window and spot cone, two-sided area lights; shadows are ROMA
// un-snapped any-hit queries with bounded steps.
#ifndef ROMA_LIGHTS_GLSL
#define ROMA_LIGHTS_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"
#include "roma/trace_descriptors.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaGbufferPixels {
    roma_gbuffer_pixel p[];
};

// 1 when the segment origin -> target is free between tmin and `shorten`
// (world units) before the target: a point light next to a surface must not be
// hidden by that surface's cells. tmin skips the cells right at the origin.
bool roma_segment_visible(vec3 origin, vec3 target, float shorten,
                          float tmin, uint max_steps)
{
    vec3 v = target - origin;
    float d = length(v);
    float tmax = d - shorten;
    if (!(tmax > tmin))
        return true;
    roma_hit h = roma_trace_unsnapped(origin, v, tmin, tmax, false, max_steps);
    return (h.info & ROMA_HIT_FLAG) == 0u;
}

// Unshadowed irradiance factor of a punctual light at p (scale * cos, 0 when
// behind the surface or outside the cone); l: unit direction to the light.
float roma_punctual_factor(roma_gpu_light light, vec3 p, vec3 gn, vec3 n, out vec3 l)
{
    uint type = uint(light.position_type.w);
    float scale = light.color_intensity.w;
    l = vec3(0.0);
    if (type == ROMA_GPU_LIGHT_DIRECTIONAL) {
        vec3 d = -light.direction_range.xyz;
        float len = length(d);
        if (!(len > 0.0))
            return 0.0;
        l = d / len;
    } else {
        vec3 d = light.position_type.xyz - p;
        float dist = length(d);
        if (!(dist > 0.0))
            return 0.0;
        l = d / dist;
        scale /= dist * dist;
        float range = light.direction_range.w;
        if (range > 0.0) {
            float q = dist / range;
            q *= q;
            scale *= max(min(1.0 - q * q, 1.0), 0.0);
        }
        if (type == ROMA_GPU_LIGHT_SPOT) {
            float cd = -dot(l, light.direction_range.xyz);
            float a = clamp(cd * light.cone.x + light.cone.y, 0.0, 1.0);
            scale *= a * a;
        }
    }
    float cos_n = dot(n, l);
    if (!(scale > 0.0) || cos_n <= 0.0 || dot(gn, l) <= 0.0)
        return 0.0;
    return min(scale * cos_n, ROMA_MAX_IRRADIANCE);
}

// Irradiance of one light: factor * colour, bounded (the colour may be large too).
vec3 roma_bounded_irradiance(float factor, vec3 color)
{
    return min(factor * color, vec3(ROMA_MAX_IRRADIANCE));
}

#endif // ROMA_LIGHTS_GLSL
