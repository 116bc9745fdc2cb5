// The public AO effect on an engine's G-buffer images (roma_ao_effect): per pixel, spp
// cosine-weighted rays, the unoccluded fraction into an R32F storage image. Samples as the
// reference tracer draws them; a device's loop budget splits them across
// dispatches (roma_ao_push.sample_first). What one ray meets is the includer's
// roma_ao_ray_open: ROMA's snapped any-hit ray (effects/ao_images.comp), or in the tools'
// study library one of the accuracy study's baselines through the same pass
// (shaders/study/ao_*.comp), so that every AO method lists, samples and writes alike.
#ifndef ROMA_AO_IMAGES_GLSL
#define ROMA_AO_IMAGES_GLSL
#define ROMA_TRACE_SET 0
// The map's BOM, bound after the images (image_effect.c), for the exact walk of the
// rays' start: bound loads are several times faster than loads by address on CPU devices.
// A baseline binds its own structure here instead.
#define ROMA_BOM_SET 1
#define ROMA_BOM_BINDING 4
#include "roma_bound_bom.glsl"
#include "roma_shared.h"
#include "roma/trace_descriptors.glsl"
#include "roma/ray_start.glsl"
#include "roma_sampling.glsl"
#include "roma_effect_surface.glsl"

// Whether the ray origin + dir * [skip, tmax] is open (meets no occupied cell); dir is
// unit and above the geometric surface. Defined by the includer.
bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax);

// Called once a pixel before its rays with the surface point and its geometric normal; the
// includer may define it (before including) to keep what its rays need of the surface.
#ifndef ROMA_AO_BEGIN
#define ROMA_AO_BEGIN(p, ng)
#endif

layout(set = 1, binding = 3, r32f) uniform image2D roma_ao_output; // read back by later parts

layout(push_constant) uniform Push { roma_ao_push pc; };

void main()
{
    uint width = pc.config.x, height = pc.config.y, spp = pc.config.z, frame = pc.config.w;
    roma_effect_surface surface;
    if (!roma_effect_surface_read(width, height, surface))
        return;
    ivec2 at = surface.at;
    // Over every pixel the uncovered ones get the background here (listed, the list pass wrote it).
    if (!surface.covered) {
        imageStore(roma_ao_output, at, vec4(1.0));
        return;
    }
    uint pixel = surface.pixel;
    vec3 n = surface.n, ng = surface.ng;
    uint seed = pc.config2.x, open = 0u;
    // Offset and skip in the trace cells of the cascade level that holds the point.
    float scale = surface.scale, skip = pc.ray.z * scale;
    precise vec3 origin = surface.p + ng * (pc.ray.x * scale);
    roma_use_ray_start(uvec2(pc.config2.w, 0u));
    ROMA_AO_BEGIN(surface.p, ng);
    // This dispatch's part of the samples; a later part adds to what the earlier ones wrote.
    for (uint k = pc.sample_first; k < min(pc.sample_end, spp); ++k) {
        ROMA_LOOP_TICK();
        uint s = frame * spp + k;
        vec3 dir = roma_local_to_world(n, roma_cosine_hemisphere(roma_random(seed, pixel, s, 0u),
                                                                 roma_random(seed, pixel, s, 1u)));
        // Below the geometric surface counts as occluded, as in the reference.
        precise float below = dir.x * ng.x + dir.y * ng.y + dir.z * ng.z;
        if (below <= 0.0)
            continue;
        open += roma_ao_ray_open(origin, dir, skip, pc.ray.y) ? 1u : 0u;
    }
    float value = float(open) / float(max(spp, 1u));
    if (pc.sample_first > 0u)
        value += imageLoad(roma_ao_output, at).x;
    // Held at 1: a GPU's approximate division may give 1.0000001 for open == spp.
    imageStore(roma_ao_output, at, vec4(min(value, 1.0)));
}

#endif // ROMA_AO_IMAGES_GLSL
