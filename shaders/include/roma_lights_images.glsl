// The body of the light effect (shaders/effects/lights_images.comp), included by it and by the accuracy
// study's variants (shaders/study/), which define ROMA_SHADOW_EXACT true first: every
// shadow segment walked exactly through the BOM (roma_lights.glsl).
#ifndef ROMA_LIGHTS_IMAGES_GLSL
#define ROMA_LIGHTS_IMAGES_GLSL
// Shadowed irradiance from punctual lights and area lights on an engine's G-buffer images
// (roma_light_effect): per pixel and punctual light one un-snapped shadow ray through the
// map bound at set 0; per area-light sample one more, the samples drawn as the reference
// draws them (dimensions 2-4, pixel y * width + x, sample frame * samples + k); formulas as
// the reference tracer's.
#define ROMA_TRACE_SET 0
// The map's BOM, bound after the images (image_effect.c), for the exact walk of the
// rays' start: bound loads are several times faster than loads by address on CPU devices.
#define ROMA_BOM_SET 1
#define ROMA_BOM_BINDING 4
#include "roma_bound_bom.glsl"
#include "roma_lights.glsl"
#include "roma_sampling.glsl"
#include "roma_effect_surface.glsl"

layout(set = 1, binding = 3, rgba32f) uniform image2D roma_light_output; // read back by later parts

layout(push_constant) uniform Push { roma_light_images_push pc; };

const uint DIM_DIRECT_AREA = 2u;
const uint DIM_MANY_LIGHTS = 10u; // the random run of lights tested a frame (lights_per_frame)

void main()
{
    uint width = pc.config.x, height = pc.config.y, light_count = pc.config.z, max_steps = pc.config.w;
    roma_effect_surface surface;
    if (!roma_effect_surface_read(width, height, surface))
        return;
    ivec2 at = surface.at;
    // Over every pixel the uncovered ones get the background here (listed, the list pass wrote it).
    if (!surface.covered) {
        imageStore(roma_light_output, at, vec4(0.0));
        return;
    }
    uint pixel = surface.pixel;
    vec3 p = surface.p, n = surface.n, ng = surface.ng;
    // Offset and skip in the trace cells of the cascade level that holds the point.
    float offset = pc.ray.x * surface.scale, tmin = pc.ray.y * surface.scale;
    vec3 origin = p + ng * offset;
    roma_use_ray_start(pc.bom);
    if (pc.surfaces != uvec2(0u))
        roma_use_surfaces(RomaSurfaceGrid(pc.surfaces).g);
    vec3 E = vec3(0.0);
    uint seed = pc.config2.x, emitter_count = pc.config2.y, samples = pc.config2.z, frame = pc.config2.w;
    // Many lights: the first `exact` lights every frame; of the `rest`, a run of `sampled`
    // consecutive ones from a random start, scaled by rest / sampled (each light is in the
    // run with probability sampled / rest, so the estimate is unbiased).
    uint exact = pc.config3.x == 0u ? light_count : min(pc.config3.y, light_count);
    uint rest = light_count - exact, sampled = min(pc.config3.x == 0u ? rest : pc.config3.x, rest);
    // This dispatch's part of the items (roma_light_images_push.part): lights [0, exact),
    // then the sampled ones, then the area-light samples; each loop runs its share of them.
    uint part_first = pc.part.x, part_end = pc.part.y;
    // roma_light_settings.output: irradiance, or the count of the lights that reach p in x.
    bool count = pc.config3.z == 1u;
    // Counting many lights walks one skip length of each ray's start (hundreds of segments a
    // pixel: the four-fold walk of the irradiance cost 35% more there).
    if (count)
        roma_start_walk = 1.0;
    for (uint i = part_first; i < min(part_end, exact); ++i) {
        ROMA_LOOP_TICK();
        E += roma_punctual_term(RomaLights(pc.lights).l[i], p, ng, n, origin, offset, tmin, max_steps, count);
    }
    if (sampled > 0u) {
        uint first =
            sampled == rest ? 0u : min(uint(roma_random(seed, pixel, frame, DIM_MANY_LIGHTS) * float(rest)), rest - 1u);
        vec3 sum = vec3(0.0);
        uint j_end = min(part_end, exact + sampled) - min(part_end, exact);
        for (uint j = max(part_first, exact) - exact; j < j_end; ++j) {
            ROMA_LOOP_TICK();
            uint i = first + j;
            i = exact + (i >= rest ? i - rest : i);
            sum += roma_punctual_term(RomaLights(pc.lights).l[i], p, ng, n, origin, offset, tmin, max_steps, count);
        }
        E += sum * (float(rest) / float(sampled));
    }
    if (emitter_count > 0u && samples > 0u) {
        vec3 area = vec3(0.0);
        uint k_end = min(part_end, exact + sampled + samples) - min(part_end, exact + sampled);
        for (uint k = max(part_first, exact + sampled) - (exact + sampled); k < k_end; ++k) {
            ROMA_LOOP_TICK();
            uint s = frame * samples + k;
            vec3 u = vec3(roma_random(seed, pixel, s, DIM_DIRECT_AREA), roma_random(seed, pixel, s, DIM_DIRECT_AREA + 1u),
                          roma_random(seed, pixel, s, DIM_DIRECT_AREA + 2u));
            area += roma_area_sample_irradiance(RomaEmitters(pc.emitters), RomaFloats(pc.cdf), emitter_count, u, p, ng,
                                                n, origin, offset, tmin, max_steps);
        }
        E += area / float(samples);
    }
    if (part_first > 0u)
        E += imageLoad(roma_light_output, at).rgb;
    imageStore(roma_light_output, at, vec4(E, 0.0));
}

#endif // ROMA_LIGHTS_IMAGES_GLSL
