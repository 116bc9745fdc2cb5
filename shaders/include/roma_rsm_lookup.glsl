// The accuracy study's GI from point and spot lights through their reflective shadow maps
// (the ROMA paper's route; src/study/study_rsm.h renders the views): a bounce hit is lit by
// a light when it is the surface that light's RSM texel holds. Include after
// roma_gi_bounce.glsl.
#ifndef ROMA_RSM_LOOKUP_GLSL
#define ROMA_RSM_LOOKUP_GLSL

#include "roma_camera.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaRsmViews { roma_rsm_view v[]; };

// Radiance leaving hit point h towards the bounce ray's origin `from`, from the view_count
// views at `views` (roma_rsm_view) of the lights at `lights`; tolerance: how much farther from
// the light than the surface its RSM texel holds h may lie and still be lit (world).
vec3 roma_rsm_radiance(vec3 h, vec3 from, uvec2 views, uint view_count, float tolerance, uvec2 lights)
{
    vec3 L = vec3(0.0);
    for (uint v = 0u; v < view_count; ++v) {
        ROMA_LOOP_TICK();
        roma_rsm_view view = RomaRsmViews(views).v[v];
        float size = float(view.info.y);
        vec3 q = roma_gbuffer_pixel_of(view.camera, h, vec2(size));
        if (!(q.z > 0.0) || q.x < 0.0 || q.y < 0.0 || q.x >= size || q.y >= size)
            continue;
        uint texel = uint(q.y) * view.info.y + uint(q.x);
        roma_gbuffer_pixel y = RomaGbufferPixels(view.info.zw).p[texel];
        if (roma_is_inf(y.position_t.w))
            continue;
        roma_gpu_light light = RomaLights(lights).l[view.info.x];
        vec3 lp = light.position_type.xyz;
        // Shadow-map test: h is lit when it is no farther from the light than the surface the light sees.
        if (distance(lp, h) > distance(lp, y.position_t.xyz) + tolerance)
            continue;
        // Only the lit side reflects (the RSM's normal faces the light): a hit on the
        // inside of a wall one cell thick may land just behind it, where the light
        // outside the room sees the wall's other face.
        if (dot(from - y.position_t.xyz, y.geometric_normal.xyz) <= 0.0)
            continue;
        vec3 l;
        float f = roma_punctual_factor(light, y.position_t.xyz, y.geometric_normal.xyz, y.shading_normal.xyz, l);
        L += y.albedo.rgb * ROMA_GI_INV_PI * roma_bounded_irradiance(f, light.color_intensity.rgb);
    }
    return L;
}

#endif // ROMA_RSM_LOOKUP_GLSL
