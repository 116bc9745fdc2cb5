/* What every public effect on the engine's G-buffer images shares: a compute pipeline
 * whose set 0 is a map's trace set and set 1 the engine's images (sampled inputs through
 * a nearest sampler, then storage outputs) followed by the map's BOM (a uniform texel buffer, for
 * the exact walk of the rays' start) and the covered-pixel list, sets allocated from a pool
 * per frame slot. Each record either lists the pixels whose position image holds a surface
 * (writing the background into the others) and dispatches the effect over the list only, or
 * dispatches it over every pixel (roma_pixel_dispatch). */
#ifndef ROMA_EFFECTS_IMAGE_EFFECT_H
#define ROMA_EFFECTS_IMAGE_EFFECT_H

#include "effects/covered_list.h"
#include "effects/slot_sets.h"
#include "roma/map.h"
#include "roma/pixel_list.h"
#include "vulkan/vk_internal.h"

#define ROMA_IMAGE_EFFECT_MAX_IMAGES 8
#define ROMA_IMAGE_EFFECT_RECORDS_PER_SLOT 16u

typedef struct roma_image_effect {
    roma_context *ctx;
    roma_logger logger;
    const char *name; /* for messages: "roma_ao_effect_record" */
    uint32_t frame; /* the settings' frame of this record */
    uint32_t inputs, outputs, push_size;
    VkSampler sampler;
    VkDescriptorSetLayout trace_layout, images_layout;
    VkPipelineLayout layout;
    int listed;                    /* the resolved roma_pixel_dispatch */
    VkPipeline list_pipeline;      /* the effect's own list pass: made when listed or first traced scaled */
    VkPipeline upsample_pipeline;  /* made by the first record traced at a resolution divisor */
    const char *list_module, *upsample_module;
    /* The effect over a list ([1]) or every pixel ([0]), with the cascade code compiled in
     * ([.][1], ROMA_PIPELINE_CASCADES) or not: the one its pixel_dispatch takes for one grid
     * made at creation, the others by the first record that needs them (a map of several
     * levels, the frame's shared list); traced: the one this record takes. */
    VkPipeline pipelines[2][2], traced;
    VkBuffer shared_list; /* this record's: the frame's roma_pixel_list, or none (its own or every pixel) */
    /* This record's resolution divisor (1, 2, 4) and the traced pixel's place in each block;
     * given_list: the record was given the frame's list (its upsample leaves uncovered pixels). */
    uint32_t scale, place[2];
    /* Entries of this record's own list: one a block (a pixel at divisor 1) when it lists
     * them itself, else 0 (the shader's binding still needs a buffer, never read). */
    uint64_t own_entries;
    int given_list;
    const char *module;
    float background[4]; /* the output where the position image holds no surface */
    roma_slot_sets sets; /* set 1 of each record */
    roma_covered_lists lists; /* each slot's own covered-pixel list */
    /* The last dispatch recorded, which roma_image_effect_dispatch_more repeats. */
    VkBuffer last_list; /* listed: its indirect arguments */
    uint32_t last_groups[2];
} roma_image_effect;

/* The nearest, clamp-to-edge sampler through which the effects read the engine's images
 * (texelFetch: any float format works). */
roma_result roma_nearest_sampler_create(roma_context *ctx, VkSampler *out);

/* inputs: the position image first (its w > 0 where it holds a surface); one output, whose
 * format list_module writes (image_list_r32f.comp or image_list_rgba32f.comp). The module's
 * specialization constant 0 says whether it traces the list (roma_image_list.glsl). */
roma_result roma_image_effect_init(roma_image_effect *e, roma_context *ctx, const roma_logger *log, const char *name,
                                   const char *module, const char *list_module, float background, uint32_t inputs,
                                   uint32_t push_size, uint32_t frames_in_flight, roma_pixel_dispatch dispatch);
void roma_image_effect_free(roma_image_effect *e);

/* A record starts a new frame of its slot when the slot or the settings' frame changed since
 * the previous record (the slot rules: the GPU is done with the slot's previous frame): the
 * slot's pool is reset then. Records of one frame (several maps) share its pool.
 * roma_image_effect_same_frame says whether this record continues one. */
int roma_image_effect_same_frame(const roma_image_effect *e, uint32_t slot);

/* Whether the images fit the dispatch (at most 65535 workgroups of 8 x 8 along each axis) and,
 * listed, their list fits one storage buffer; the record's argument check, before anything is
 * recorded (name: the record's, for the message). */
roma_result roma_image_effect_check_size(const roma_image_effect *e, const char *name, uint32_t width,
                                         uint32_t height);

/* Checks slot, map, the frame's shared list (pixels, optional: recorded in the slot for
 * width x height) and the resolution divisor (0 or 1: every pixel traced; 2 or 4: one pixel
 * of each 2 x 2 or 4 x 4 block, its place in the block new each frame, the rest upsampled by
 * roma_image_effect_finish); the map's info is returned for the push. */
roma_result roma_image_effect_begin(roma_image_effect *e, uint32_t slot, uint32_t frame, const roma_map *map,
                                    const roma_pixel_list *pixels, uint32_t width, uint32_t height,
                                    uint32_t resolution_divisor, roma_map_info *info);

/* Whether a settings' resolution_divisor is one the effects take (0, 1, 2, 4). */
int roma_image_effect_divisor_valid(uint32_t resolution_divisor);
/* Allocates and writes set 1 (views: inputs then the output), then records, with push, the
 * effect's dispatch over ceil(width / 8) x ceil(height / 8) workgroups or, listed, the
 * covered-pixel list of the position image (a list pass over those workgroups, which writes
 * the background elsewhere, and its dispatch's arguments) and the effect's indirect dispatch
 * over it, or, with the frame's shared list (begin's pixels), the indirect dispatch over that
 * alone. The slot's own list grows here when the images do. */
roma_result roma_image_effect_dispatch(roma_image_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                       const roma_map_info *info, const VkImageView *views, VkImageLayout input_layout,
                                       const void *push, uint32_t width, uint32_t height);

/* One more dispatch of the effect right after roma_image_effect_dispatch (or this), in the
 * same command buffer with nothing recorded between: the same pixels and bindings, another
 * push (the next part of work a device's loop budget splits, src/vulkan/loop_budget.h),
 * after a barrier so that it reads what the dispatch before it wrote to the output. */
void roma_image_effect_dispatch_more(roma_image_effect *e, VkCommandBuffer cmd, const void *push);

/* After the last dispatch of a record traced at a resolution divisor: the upsample of the
 * traced pixels into the others (after a barrier), with the same bindings; else nothing. */
void roma_image_effect_finish(roma_image_effect *e, VkCommandBuffer cmd, uint32_t width, uint32_t height);

#endif /* ROMA_EFFECTS_IMAGE_EFFECT_H */
