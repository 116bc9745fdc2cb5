/* Renders the effects of a scene with ROMA over a number of frames from a
 * still camera and returns converged images (internal; used by roma-render,
 * the tests and the benchmark). Runs only the passes of the effect plan
 * (roma/effects.h): G-buffer once, then per frame every ROMA array the plan
 * needs is rebuilt with new grid and direction jitter and every planned pass
 * adds its estimates to its accumulation buffer; images are resolved on the
 * host at the end.
 *
 * Samples: frame f uses sample indices f * spp .. f * spp + spp - 1 with the
 * reference's random dimensions (src/reference/reference.h), so the Embree
 * reference at spp * frames samples draws the same directions and light points.
 * Shadow rays start offset_cells trace cells along the geometric normal, skip
 * their first skip_cells trace cells (tmin; AO and GI rays ao_skip_cells), and end the origin offset short of
 * a point light or the same offset off an area light's surface. Without the
 * skip, rays leaving a point near a wall meet that wall's cells (contact
 * over-darkening); without the offset at the light's end, rays reaching an area
 * light at a grazing angle meet the cells of the surface it is mounted on
 * (docs/accuracy.md has the measurements behind both). */
#ifndef ROMA_PASSES_EFFECT_RENDER_H
#define ROMA_PASSES_EFFECT_RENDER_H

#include "roma/camera.h"
#include "roma/context.h"
#include "roma/effects.h"
#include "roma/image.h"
#include "roma/map.h"
#include "passes/ao.h"
#include "roma_shared.h"
#include "study/study_shadows.h"

/* ROMA_DEFAULT_AO_SKIP_CELLS (roma/ao_effect.h): AO and GI rays skip their first 1.6 trace
 * cells, with the exact BOM the value that keeps the worst of the three converged AO scenes
 * lowest (docs/accuracy.md). */
#include "roma/ao_effect.h"
#include "roma/light_effect.h"


typedef struct roma_effect_render_desc {
    roma_camera camera;
    uint32_t width, height;
    roma_effect_options options;       /* effects, RES, A per pass, many-light count */
    uint32_t spp;                      /* per frame, AO and area lights; 0 = ROMA_DEFAULT_AO_SAMPLES (1) */
    uint32_t frames;                   /* 0 = 1 */
    uint32_t seed;
    float ao_radius;                   /* <= 0: unbounded */
    float offset_cells;                /* 0 = ROMA_DEFAULT_OFFSET_CELLS */
    float skip_cells;                  /* shadow rays' tmin in trace cells; 0 = ROMA_DEFAULT_SHADOW_SKIP_CELLS (1),
                                          negative = none */
    float ao_skip_cells;               /* the same for AO and GI bounce rays; 0 = ROMA_DEFAULT_AO_SKIP_CELLS,
                                          negative = none */
    uint32_t max_steps;                /* un-snapped shadow rays of direct light; 0 = ROMA_DEFAULT_SHADOW_STEPS (8, paper) */
    /* What AO rays trace (passes/ao.h): ROMA (0, the default) or a baseline of the accuracy
     * study: the exact traversal of the BOM (3D DDA from each ray's origin to its end, no
     * ROMA maps: the voxelization's error apart from ROMA's), or the distance field built
     * from the BOM every frame and sphere-traced (the ROMA paper's comparator), or the NAADF
     * hierarchy built from the BOM every frame (the exact traversal's voxels, empty space left
     * a box at a time), or screen-space AO against the G-buffer's depth (AO alone, bounded
     * radius; no map is built). */
    roma_ao_method ao_method;
    /* What the rays of the light passes trace: ROMA (0, the default) or the exact traversal
     * of the BOM (the accuracy study's baseline): the shadow rays of direct light (point,
     * spot, directional and area lights) and of many lights to their end, GI's bounce rays
     * to their first occupied cell and the shadow rays at their hits (point and spot lights
     * through RSMs stay RSMs). Both take an area-light segment whose offset ends cross the
     * other surface's plane (two surfaces closer than an offset) as free
     * (roma_area_sample_irradiance). */
    roma_shadow_method shadow_method;
    uint32_t ssao_steps;               /* ROMA_AO_METHOD_SCREEN_SPACE: march steps; 0 = ROMA_AO_SSAO_STEPS */
    /* ROMA_AO_METHOD_SCREEN_SPACE: the layers of a stochastic depth map rasterized every frame
     * beside the G-buffer's depth (0: none, at most ROMA_AO_SSAO_MAX_LAYERS), each keeping a
     * fragment with probability ssao_keep (0 = ROMA_AO_SSAO_KEEP; 1: every layer is the
     * G-buffer's depth again). */
    uint32_t ssao_layers;
    float ssao_keep;
    /* 1: rays skip their first cells without looking (the rule before the exact walk of
     * roma/ray_start.glsl, which keeps rays from passing a wall they start next to). */
    int blind_ray_start;
    uint32_t lights_max_steps;         /* un-snapped rays of the many-lights pass; 0 = 16 */
    uint32_t rsm_size;                 /* reflective shadow map views, square; 0 = 256 */
    /* A GI hit counts as lit when it is no farther from the light than the surface
     * its RSM texel holds plus this many trace cells. 0 (the default) measured best:
     * a closest hit lies on the entry face of its cell, in front of the surface. */
    float rsm_tolerance_cells;
    /* GI from point and spot lights: 0 = through their reflective shadow maps (the ROMA
     * paper's route, the default: the more accurate of the two on cornell_spot,
     * docs/accuracy.md), 1 = one ROMA shadow ray per light at each bounce hit (no RSM
     * pass). Area and directional lights always take shadow rays. */
    int gi_punctual_rays;
    uint32_t lights_per_frame;         /* many lights tested per pixel and frame; 0 = all (exact) */
    const float *many_light_positions; /* 3 floats per light; required for ROMA_EFFECT_LIGHTS */
    /* Interactive mode: one camera per frame (`camera` is then unused). The
     * G-buffer is rendered every frame with motion vectors, each frame's samples
     * are resolved on the GPU, accumulated over frames with reprojection and
     * disocclusion rejection, and the last frame's history goes through an
     * edge-aware a-trous filter; the images are that last frame. */
    const roma_camera *camera_path;
    uint32_t max_history;              /* frames averaged at most; 0 = 32 */
    uint32_t filter_iterations;        /* a-trous iterations (steps 1, 2, 4, ...); 0 = 3 */
    int no_spatial_filter;             /* 1: the accumulated history as it is */
    float filter_luminance_sigma;      /* value edge-stopping, in noise units (see atrous.comp); 0 = 1 */
    /* Optional outputs for evaluation (caller-allocated, width * height entries):
     * the G-buffer, and per pixel ceil(count / 32) words of many-light visibility
     * of the last frame (exact mode only: left untouched when lights_per_frame
     * tests fewer than all lights). */
    roma_gbuffer_pixel *out_gbuffer;
    uint32_t *out_light_mask;
    /* Called after each frame's submission has finished, with frames done / frames. */
    void (*progress)(float fraction, void *user_data);
    void *progress_user_data;
} roma_effect_render_desc;

/* Same layout as the reference's images: ao 1 channel (background 1), direct and
 * gi RGB (background 0), lights 1 channel visible-light count (background 0),
 * coverage 1 where the G-buffer saw geometry. Effects not asked for stay zeroed. */
typedef struct roma_effect_images {
    roma_image ao, direct, gi, lights, coverage;
} roma_effect_images;

typedef struct roma_effect_stats {
    roma_effect_plan plan;
    double pass_ms[ROMA_PASS_COUNT];   /* GPU timestamps summed over frames (gbuffer: once) */
    double build_ms[ROMA_PASS_COUNT];  /* per array in plan.maps: BOM + rotation, summed over frames */
    roma_map_info map_info[ROMA_PASS_COUNT];
    uint64_t pass_bytes[ROMA_PASS_COUNT]; /* GPU memory of each pass's own buffers */
    /* ROMA_AO_METHOD_DISTANCE_FIELD and ROMA_AO_METHOD_NAADF: the builds of the structure the
     * baseline makes from the BOM every frame (GPU timestamps summed over frames, also in the
     * AO pass's time), its memory and what it uses only while building (the field's seeds);
     * with ssao_layers: the stochastic depth map's rasterization (not in the AO pass's time). */
    double baseline_build_ms;
    uint64_t baseline_bytes, baseline_build_bytes;
} roma_effect_stats;

roma_result roma_effect_render(roma_context *ctx, const roma_scene *scene, const roma_effect_render_desc *desc,
                               roma_effect_images *out_images, roma_effect_stats *out_stats);
void roma_effect_images_free(roma_effect_images *images);

#endif /* ROMA_PASSES_EFFECT_RENDER_H */
