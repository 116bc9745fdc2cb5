/* The tools' ROMA images (roma-render, roma-bench's study) through libroma's public effect
 * API, as an engine records them: the tool is the engine. Its G-buffer is the reference
 * tracer's primary rays (pixel centres, the points the Embree reference shades), uploaded into
 * images it owns; every frame it records, into one command buffer of its own, the build of
 * each ROMA array the effect plan needs (new jitter each frame) and the AO, light and GI
 * effects on those images, then copies their outputs to the host, submits, waits and adds
 * them up: the accumulation over frames is a loop around the public passes. Frame f uses
 * samples f*spp .. f*spp+spp-1, as the reference at spp*frames samples does.
 *
 * The accuracy study's methods (its AO baselines and stochastic depth map, exact shadow rays,
 * the blind ray start, GI through reflective shadow maps) plug into the same passes from the
 * tools' study library (src/study/). */
#ifndef ROMA_APPS_EFFECT_API_H
#define ROMA_APPS_EFFECT_API_H

#include <stdint.h>

#include "reference.h"
#include "roma_shared.h"
#include "study/study_methods.h"
#include "roma/roma.h"

typedef struct effect_api_desc {
    roma_camera camera;
    uint32_t width, height;
    roma_effect_options options; /* effects (ao, direct, gi), RES, A per pass */
    uint32_t spp;                /* per frame: AO rays, area-light samples, GI bounces; 0 = 1 */
    uint32_t frames;             /* 0 = 1 */
    uint32_t seed;
    float ao_radius;             /* <= 0 or infinite: unbounded */
    /* As the public settings take them: 0 = the library's default, a negative skip = none. */
    float offset_cells, skip_cells, ao_skip_cells;
    uint32_t max_steps;
    roma_pixel_dispatch pixel_dispatch; /* the three effects' */
    /* The covered pixels listed once (roma_pixel_list) and given to every effect of every
     * frame: the G-buffer does not change between frames. */
    int shared_list;
    /* Many lights (options.effects ROMA_EFFECT_LIGHTS): options.many_light_count positions
     * (3 floats each) of unit point lights, lights_per_frame of them tested per pixel and frame
     * (0: all): the light effect's count of visible lights (ROMA_LIGHT_OUTPUT_VISIBLE_COUNT). */
    const float *many_light_positions;
    uint32_t lights_per_frame;
    uint32_t lights_max_steps;   /* the count's un-snapped segments' step bound; 0 = 16 */
    uint32_t resolution_divisor; /* the three effects': 0 or 1 every pixel, 2 or 4 (roma_ao_settings) */
    /* Cascade levels of every array (at most what its A allows: K x A x A <= 256; 0 = 1),
     * centred on the camera's eye, the finest cube's edge finest_extent (0: the library's). */
    uint32_t cascades;
    float finest_extent;
    int jitter_off; /* every frame's grid placement and directions the first frame's */
    /* The study's methods (study/study_methods.h): what AO rays trace (0 ROMA) and the
     * screen-space march's steps (0: the default); what shadow, bounce and visibility rays
     * trace (0 ROMA); blind_start: ROMA's rays skip their start unseen; ao_start, ao_trace: how
     * ROMA's AO rays' start is checked and the rest traced (the public settings). */
    roma_ao_method ao_method;
    roma_shadow_method shadow_method;
    int blind_start;
    roma_ao_start ao_start;
    roma_ao_trace ao_trace;
    uint32_t ssao_steps;
    /* Screen-space AO: the layers of a stochastic depth map rasterized every frame beside the
     * G-buffer (0: none; study/study_depth_layers.h), each keeping a fragment with probability
     * ssao_keep (0 = ROMA_AO_SSAO_KEEP). */
    uint32_t ssao_layers;
    float ssao_keep;
    /* Non-NULL: those layers ray traced through it instead (the seed paper's acquisition,
     * study/hw_ray_tracing.h; made from the same scene on the render's context). */
    struct roma_hwrt *ssao_traced;
    /* GI from point and spot lights through their reflective shadow maps (study/study_rsm.h:
     * rsm_size square views, 0 = 256; a hit up to rsm_tolerance_cells trace cells farther from
     * the light than its texel's surface is lit) instead of shadow rays. */
    int gi_rsm;
    uint32_t rsm_size;
    float rsm_tolerance_cells;
    void (*progress)(float fraction, void *user_data); /* after each frame */
    void *progress_user_data;
} effect_api_desc;

typedef struct effect_api_result {
    /* ao 1 channel (1 where nothing was seen), direct and gi RGB radiance (albedo / pi times the
     * effects' irradiance), coverage 1 where a primary ray hit: the reference's layout. */
    roma_image ao, direct, gi, lights, coverage;
    roma_effect_plan plan;
    roma_map_info map_info[ROMA_PASS_COUNT]; /* per array of plan.maps */
    double build_ms[ROMA_PASS_COUNT];        /* per array: GPU timestamps summed over frames */
    double ao_ms, direct_ms, gi_ms, lights_ms; /* each effect's records: GPU timestamps summed */
    double list_ms;                          /* desc.shared_list: the one list's record */
    double gbuffer_ms;                       /* the primary rays, host clock */
    /* Every frame from submit to fence, host clock, summed: the arrays' builds, the effects and
     * the copy of their outputs to the host (what a frame costs where timestamps do not cover
     * dispatches, as on lavapipe). */
    double frames_ms;
    uint64_t effect_bytes;                   /* the G-buffer, output and transfer memory made here */
    /* A study AO method's structure built every frame (distance field, NAADF): its builds'
     * GPU time summed over frames (also in ao_ms), its memory and what only its build uses. */
    double baseline_build_ms;
    uint64_t baseline_bytes, baseline_build_bytes;
    double rsm_ms;      /* desc.gi_rsm: the views' rasterization (the first frame's) */
    uint64_t rsm_bytes; /* their memory */
    double depth_layers_ms;      /* desc.ssao_layers: their acquisition, summed over frames (not in ao_ms) */
    uint64_t depth_layers_bytes; /* their memory */
} effect_api_result;

/* The G-buffer effect_api_render shades (the reference's primary rays through the pixel
 * centres) as width * height roma_gbuffer_pixel: position_t.w the distance from the eye, +INF
 * where nothing is seen (the rest zero), albedo.w the bits of the triangle's index. */
roma_result effect_api_gbuffer(const roma_ref *ref, const roma_camera *camera, uint32_t width, uint32_t height,
                              roma_gbuffer_pixel *out);

roma_result effect_api_render(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                              const effect_api_desc *desc, effect_api_result *out);
void effect_api_result_free(effect_api_result *result);

#endif /* ROMA_APPS_EFFECT_API_H */
