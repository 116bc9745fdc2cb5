/* Ambient-occlusion pass (internal for now).
 *
 * Reads the G-buffer (study/gbuffer.h) and, per covered pixel, traces spp
 * cosine-weighted directions around the shading normal (include/roma/sampling.h,
 * sample index frame * spp + k, dimensions 0 and 1) as snapped any-hit queries
 * through a built ROMA map. Directions below the geometric surface count as
 * occluded; origins are offset along the geometric normal. The number of
 * unoccluded samples is added to a uint per pixel, so frames accumulate:
 * AO = accum / (spp * frames). Background pixels (t = +INF) add nothing. */
#ifndef ROMA_PASSES_AO_H
#define ROMA_PASSES_AO_H

#include <vulkan/vulkan.h>

#include "roma/camera.h"
#include "roma/context.h"
#include "roma/map.h"
#include "study/study_methods.h"

typedef struct roma_ao_pass roma_ao_pass;

typedef struct roma_ao_pass_inputs {
    VkBuffer gbuffer_pixels;        /* width * height roma_gbuffer_pixel */
    uint32_t width, height;
    const roma_map_info *map;       /* of a built map: its maps view and parameters buffer */
    const struct roma_gbuffer_list *list; /* covered pixels of this G-buffer (recorded before) */
    float offset;                   /* origin offset in world units (offset_cells * trace_cell) */
    float radius;                   /* <= 0: unbounded */
    float tmin;                     /* world units skipped at the start of each ray (>= 0) */
    /* The map's BOM as a texel buffer (roma_map_info.bom_view), bound: the skipped start is
     * walked through it exactly, an occupied cell blocking the ray (roma/ray_start.glsl).
     * With ROMA_AO_METHOD_DISTANCE_FIELD: the field's distances (distances_view) instead;
     * with ROMA_AO_METHOD_NAADF: the hierarchy's cells (cells_view). */
    VkBufferView bom;
    int blind_start;                /* 1: the start is skipped unseen (the rule before the walk) */
    uint32_t spp, frame, seed;
    /* ROMA_AO_METHOD_SCREEN_SPACE: the camera the G-buffer was rendered with, and the march's
     * steps (0 = ROMA_AO_SSAO_STEPS). */
    const roma_camera *camera;
    uint32_t ssao_steps;
    /* ... and the stochastic depth map's layers beside the G-buffer's depth (0: none), bound
     * in place of the BOM (bom: an RGBA32_UINT view of ssao_layers G-buffers one after the
     * other). */
    uint32_t ssao_layers;
    /* width * height uint32_t, added to; clear it (vkCmdFillBuffer) before frame 0. */
    VkBuffer accum;
} roma_ao_pass_inputs;

roma_result roma_ao_pass_create(roma_context *ctx, roma_ao_pass **out);
/* The same for a method other than ROMA's. */
roma_result roma_ao_pass_create_mode(roma_context *ctx, roma_ao_method method, roma_ao_pass **out);
/* Accepts NULL. */
void roma_ao_pass_destroy(roma_ao_pass *pass);

/* Records the pass into cmd (outside any rendering). The buffers are bound through a
 * descriptor set made for each distinct combination of map, G-buffer, list and
 * accumulator (at most ROMA_PIXEL_PASS_MAX_SETS per pass, passes/pixel_pass.h). Makes earlier compute and
 * fragment writes (G-buffer) and transfer writes (the clear) visible first; the
 * accumulation buffer is then visible to compute and transfer reads. */
roma_result roma_ao_pass_record(roma_ao_pass *pass, VkCommandBuffer cmd, const roma_ao_pass_inputs *in);

#endif /* ROMA_PASSES_AO_H */
