// The body of the GI effect (shaders/effects/gi_images.comp), included by it and by the accuracy
// study's variants (shaders/study/), which define ROMA_SHADOW_EXACT true first (every
// shadow segment walked exactly through the BOM, roma_lights.glsl) or ROMA_GI_RSM_LOOKUP
// (point and spot lights read from reflective shadow maps at bounce hits).
#ifndef ROMA_GI_IMAGES_GLSL
#define ROMA_GI_IMAGES_GLSL
// One-bounce diffuse GI on an engine's G-buffer images (roma_gi_effect): per pixel,
// samples cosine-weighted bounce rays (dimensions 5 and 6, pixel y * width + x, sample
// frame * samples + k) through the map bound at set 0, each hit lit as in
// roma_gi_bounce.glsl; writes E = pi * the mean radiance of the hits (cosine sampling
// cancels cos / pi).
#define ROMA_TRACE_SET 0
// The map's BOM, bound after the images (image_effect.c), for the exact walk of the
// rays' start: bound loads are several times faster than loads by address on CPU devices.
#define ROMA_BOM_SET 1
#define ROMA_BOM_BINDING 4
#include "roma_bound_bom.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_gi_bounce.glsl"
#ifdef ROMA_GI_RSM_LOOKUP
#include "roma_rsm_lookup.glsl"
#endif
#include "roma_effect_surface.glsl"

layout(set = 1, binding = 3, rgba32f) uniform image2D roma_gi_output; // read back by later parts

layout(push_constant) uniform Push { roma_gi_images_push pc; };

void main()
{
#ifdef ROMA_GI_EXACT_FROM_PUSH
    // The study's exact rays, switched on by the push (config2.w) rather than fixed at compile
    // time: compiled with the switch fixed, lavapipe (Mesa 22.3) leaks its JIT's memory.
    roma_shadow_exact = pc.config2.w != 0u;
#endif
    uint width = pc.config.x, height = pc.config.y, samples = pc.config.z, frame = pc.config.w;
    roma_effect_surface surface;
    if (!roma_effect_surface_read(width, height, surface))
        return;
    ivec2 at = surface.at;
    // Over every pixel the uncovered ones get the background here (listed, the list pass wrote it).
    if (!surface.covered || pc.scene == uvec2(0u)) {
        imageStore(roma_gi_output, at, vec4(0.0));
        return;
    }
    uint pixel = surface.pixel;
    vec3 n = surface.n, ng = surface.ng;
    // Offset and skip in the trace cells of the cascade level that holds the point (the
    // shadow rays at a bounce hit: in the hit's, roma_gi_hit_radiance).
    float scale = surface.scale;
    vec3 origin = surface.p + ng * (pc.ray.x * scale);
    roma_use_ray_start(pc.bom);
    roma_gi_scene S = RomaGiScene(pc.scene).s;
    if (pc.bom != uvec2(0u)) // the blind-start baseline walks nothing at a light's end either
        roma_use_surfaces(S.surfaces);
    uint seed = pc.config2.x;
    roma_gi_shading P = roma_gi_shading(pc.ray.x, pc.ray.z, pc.config2.y, seed, pc.lights, pc.part.zw);
    vec3 acc = vec3(0.0);
    for (uint k = pc.part.x; k < min(pc.part.y, samples); ++k) { // this dispatch's part
        ROMA_LOOP_TICK();
        uint s = frame * samples + k;
        vec3 dir = roma_local_to_world(n, roma_cosine_hemisphere(roma_random(seed, pixel, s, ROMA_DIM_GI_BOUNCE),
                                                                 roma_random(seed, pixel, s, ROMA_DIM_GI_BOUNCE + 1u)));
        if (dot(dir, ng) <= 0.0)
            continue;
        bool hit;
        vec3 hit_point;
        acc += roma_gi_bounce(S, P, origin, dir, pc.ray.y * scale, true, pixel, s, hit, hit_point);
#ifdef ROMA_GI_RSM_LOOKUP // the study's RSM route (roma_rsm_lookup.glsl), with the first lights' part
        if (hit && pc.part.z == 0u)
            acc += roma_rsm_radiance(hit_point, origin, pc.views, pc.config2.z, pc.ray.w, pc.lights);
#endif
    }
    vec3 E = acc * (3.14159265358979 / float(samples));
    if (pc.part.x > 0u || pc.part.z > 0u) // a later part adds to the earlier ones
        E += imageLoad(roma_gi_output, at).rgb;
    imageStore(roma_gi_output, at, vec4(E, 0.0));
}

#endif // ROMA_GI_IMAGES_GLSL
