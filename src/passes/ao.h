/* Ambient-occlusion pass (internal for now).
 *
 * Reads the G-buffer (passes/gbuffer.h) and, per covered pixel, traces spp
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

/* What the AO rays trace: ROMA, or one of the accuracy study's baselines. */
typedef enum roma_ao_method {
    ROMA_AO_METHOD_ROMA = 0,
    /* every ray walked exactly through the map's BOM from its origin to its end (3D DDA,
     * Amanatides-Woo): the same voxels without snapping, rotation or bounded steps */
    ROMA_AO_METHOD_VOXEL_DDA = 1,
    /* every ray sphere-traced from its origin through the distance field built from the
     * map's BOM (baselines/distance_field.h), bound in the BOM's place, at most
     * ROMA_AO_DF_MAX_STEPS steps of at least ROMA_AO_DF_MIN_STEP cells */
    ROMA_AO_METHOD_DISTANCE_FIELD = 2,
    /* every ray marched in screen space against the G-buffer's depth layer, and the layers
     * of a stochastic depth map if given (shaders/include/roma_ssao.glsl): no map is read,
     * and a bounded radius is needed */
    ROMA_AO_METHOD_SCREEN_SPACE = 3,
    /* every ray traversed from its origin through the NAADF hierarchy built from the map's BOM
     * (baselines/naadf.h), bound in the BOM's place: the voxels of ROMA_AO_METHOD_VOXEL_DDA,
     * empty space left a box at a time */
    ROMA_AO_METHOD_NAADF = 4,
} roma_ao_method;

/* The screen-space baseline's march: steps per ray, and how far behind its depth a surface
 * is taken to extend, as a fraction of the AO radius. */
#define ROMA_AO_SSAO_STEPS 16u
#define ROMA_AO_SSAO_THICKNESS 0.5f
/* The stochastic depth map beside the G-buffer's depth: at most this many layers, each
 * keeping a fragment with this probability (a pixel's k-th surface from the eye is in a
 * layer with probability 0.5^k). */
#define ROMA_AO_SSAO_MAX_LAYERS 8u
#define ROMA_AO_SSAO_KEEP 0.5f

/* The ROMA paper's baseline takes up to 64 steps. With half a cell as the least step a ray
 * can clip only the corner of an occupied cell: closed rooms leak on under 0.5% of their
 * pixels (tests/test_closed_rooms.c). */
#define ROMA_AO_DF_MAX_STEPS 64u
#define ROMA_AO_DF_MIN_STEP 0.5f

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
