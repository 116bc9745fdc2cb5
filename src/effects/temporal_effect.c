/* roma_temporal_effect: temporal accumulation with reprojection
 * (shaders/effects/temporal_images.comp) and an edge-aware a-trous filter
 * (shaders/effects/atrous_images.comp) on the engine's images; descriptor sets from a pool
 * per frame slot, reset when a record starts a new frame of its slot. */
#include "roma/temporal_effect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "effects/image_effect.h"
#include "effects/slot_sets.h"
#include "roma_shared.h"
#include "util/log.h"
#include "vulkan/vk_internal.h"

#define RECORDS_PER_SLOT 8u
#define SETS_PER_RECORD (1u + ROMA_MAX_FILTER_ITERATIONS)
#define TEMPORAL_SAMPLED 4u /* current, position, previous_position, history; then accumulated */
#define ATROUS_SAMPLED 2u   /* position, normal; then src, dst */

struct roma_temporal_effect {
    roma_context *ctx;
    roma_logger logger;
    VkSampler sampler;
    roma_compute_pipeline temporal, atrous;
    roma_slot_sets sets;
};

static int finite_all(const float *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

roma_result roma_temporal_settings_resolve(const roma_temporal_settings *in, roma_temporal_settings *out)
{
    roma_temporal_settings s = in ? *in : (roma_temporal_settings){0};
    if (out)
        memset(out, 0, sizeof *out);
    if (!out)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_temporal_settings_resolve: out is NULL");
    if (!finite_all(s.previous_view_proj, 16))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_temporal_settings: previous_view_proj has a NaN or infinite entry");
    if (s.filter_iterations > ROMA_MAX_FILTER_ITERATIONS)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_temporal_settings: filter_iterations %u, at most %u",
                         s.filter_iterations, ROMA_MAX_FILTER_ITERATIONS);
    if (s.max_history == 0)
        s.max_history = ROMA_DEFAULT_TEMPORAL_HISTORY;
    if (s.filter_iterations == 0)
        s.filter_iterations = ROMA_DEFAULT_FILTER_ITERATIONS;
    if (s.filter_below == 0)
        s.filter_below = ROMA_DEFAULT_FILTER_BELOW;
    *out = s;
    return ROMA_SUCCESS;
}

void roma_temporal_effect_destroy(roma_temporal_effect *e)
{
    if (!e)
        return;
    roma_context *ctx = e->ctx;
    roma_slot_sets_free(&e->sets);
    roma_compute_pipeline_destroy(ctx, &e->temporal);
    roma_compute_pipeline_destroy(ctx, &e->atrous);
    if (e->sampler)
        vkDestroySampler(ctx->device, e->sampler, ctx->allocator);
    free(e);
}

roma_result roma_temporal_effect_create(roma_context *ctx, const roma_temporal_effect_desc *desc_in,
                                        roma_temporal_effect **out)
{
    roma_temporal_effect_desc desc = desc_in ? *desc_in : (roma_temporal_effect_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_temporal_effect_create: out is NULL");
    *out = NULL;
    if (!ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_temporal_effect_create: context is NULL");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_temporal_effect_create: frames_in_flight %u outside [1, %u]", desc.frames_in_flight,
                         ROMA_MAX_FRAMES_IN_FLIGHT);
    roma_temporal_effect *e = calloc(1, sizeof *e);
    if (!e)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_temporal_effect_create: out of host memory");
    e->ctx = ctx;
    e->logger = *log;
    roma_result r = roma_nearest_sampler_create(ctx, &e->sampler);
    const VkDescriptorType temporal_types[TEMPORAL_SAMPLED + 1] = {
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    const VkDescriptorType atrous_types[ATROUS_SAMPLED + 2] = {
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "temporal_images.comp", temporal_types, TEMPORAL_SAMPLED + 1,
                                               sizeof(roma_temporal_images_push), &e->temporal);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "atrous_images.comp", atrous_types, ATROUS_SAMPLED + 2,
                                               sizeof(roma_atrous_images_push), &e->atrous);
    /* Per record: the temporal pass's set and one per filter iteration. */
    const VkDescriptorPoolSize sizes[2] = {
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, TEMPORAL_SAMPLED + ATROUS_SAMPLED * ROMA_MAX_FILTER_ITERATIONS},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1u + 2u * ROMA_MAX_FILTER_ITERATIONS}};
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_init(&e->sets, ctx, desc.frames_in_flight, RECORDS_PER_SLOT, SETS_PER_RECORD, sizes, 2);
    if (r != ROMA_SUCCESS) {
        roma_temporal_effect_destroy(e);
        return roma_fail(log, r, "roma_temporal_effect_create: cannot create the pipelines or pools");
    }
    *out = e;
    return ROMA_SUCCESS;
}

/* Compute-shader storage writes before the next dispatch's reads (and its writes over what
 * the one before read). */
static void compute_barrier(VkCommandBuffer cmd)
{
    VkMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                          .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          .srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          .dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    VkDependencyInfo d = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &d);
}

static void dispatch(VkCommandBuffer cmd, const roma_compute_pipeline *p, VkDescriptorSet set, const void *push,
                     uint32_t push_size, uint32_t width, uint32_t height)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size, push);
    vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
}

roma_result roma_temporal_effect_record(roma_temporal_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                        const roma_temporal_images *im, const roma_temporal_settings *settings_in)
{
    const roma_logger *log = e ? &e->logger : NULL;
    if (!e || !cmd || !im)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_temporal_effect_record: %s is NULL",
                         !e ? "effect" : !cmd ? "cmd" : "images");
    roma_temporal_settings s;
    roma_result r = roma_temporal_settings_resolve(settings_in, &s);
    if (r != ROMA_SUCCESS)
        return roma_fail(log, r, "roma_temporal_effect_record: invalid settings");
    if (!im->width || !im->height || !im->current || !im->position || !im->normal || !im->accumulated)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_temporal_effect_record: width, height, current, position, normal and accumulated "
                         "are required");
    if (!s.reset && (!im->history || !im->previous_position))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_temporal_effect_record: history and previous_position are required without reset");
    /* An image written by a dispatch must not be read or written by another view in it. */
    VkImageView written[3] = {im->accumulated, im->filtered, im->scratch};
    const VkImageView read[5] = {im->current, im->position, im->normal, im->previous_position, im->history};
    for (int w = 0; w < 3; ++w) {
        for (int q = 0; written[w] && q < 5; ++q)
            if (written[w] == read[q])
                return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                                 "roma_temporal_effect_record: an output image is also an input");
        for (int o = w + 1; written[w] && o < 3; ++o)
            if (written[w] == written[o])
                return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                                 "roma_temporal_effect_record: accumulated, filtered and scratch must differ");
    }
    if (im->filtered && s.filter_iterations > 1 && !im->scratch)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_temporal_effect_record: %u filter iterations need a scratch image", s.filter_iterations);
    r = roma_slot_sets_begin(&e->sets, log, "roma_temporal_effect_record", slot, s.frame);
    if (r != ROMA_SUCCESS)
        return r;
    VkImageLayout input = im->input_layout ? im->input_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkImageLayout history = im->history_layout ? im->history_layout : VK_IMAGE_LAYOUT_GENERAL;
    /* With reset the history is not read: the current image stands in for the absent views. */
    const VkImageView tviews[TEMPORAL_SAMPLED + 1] = {
        im->current, im->position, im->previous_position ? im->previous_position : im->current,
        im->history ? im->history : im->current, im->accumulated};
    const VkImageLayout tlayouts[TEMPORAL_SAMPLED] = {input, input, input, im->history ? history : input};
    VkDescriptorSet sets[SETS_PER_RECORD];
    uint32_t iterations = im->filtered ? s.filter_iterations : 0;
    r = roma_slot_sets_write_images(&e->sets, slot, e->temporal.set_layout, e->sampler, tviews, tlayouts,
                                    TEMPORAL_SAMPLED, TEMPORAL_SAMPLED + 1, &sets[0]);
    /* Iteration i writes filtered when iterations - 1 - i is even, scratch otherwise, so the
     * last one ends in filtered; each reads what the one before wrote. */
    VkImageView src = im->accumulated;
    for (uint32_t i = 0; i < iterations && r == ROMA_SUCCESS; ++i) {
        VkImageView dst = (iterations - 1 - i) % 2 == 0 ? im->filtered : im->scratch;
        const VkImageView aviews[ATROUS_SAMPLED + 2] = {im->position, im->normal, src, dst};
        const VkImageLayout alayouts[ATROUS_SAMPLED] = {input, input};
        r = roma_slot_sets_write_images(&e->sets, slot, e->atrous.set_layout, e->sampler, aviews, alayouts,
                                        ATROUS_SAMPLED, ATROUS_SAMPLED + 2, &sets[1 + i]);
        src = dst;
    }
    if (r != ROMA_SUCCESS)
        return roma_fail(log, r, "roma_temporal_effect_record: cannot allocate descriptor sets");
    roma_slot_sets_commit(&e->sets, slot);

    int still = 1;
    for (int i = 0; i < 16; ++i)
        still &= s.previous_view_proj[i] == 0.0f;
    roma_temporal_images_push tp = {
        .config = {im->width, im->height, s.max_history,
                   (s.reset ? ROMA_TEMPORAL_RESET : 0u) | (still ? ROMA_TEMPORAL_STILL : 0u)}};
    float *rows[4] = {tp.prev_row0, tp.prev_row1, tp.prev_row2, tp.prev_row3};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            rows[row][col] = s.previous_view_proj[col * 4 + row]; /* column-major in, rows out */
    dispatch(cmd, &e->temporal, sets[0], &tp, sizeof tp, im->width, im->height);
    for (uint32_t i = 0; i < iterations; ++i) {
        compute_barrier(cmd);
        roma_atrous_images_push ap = {.config = {im->width, im->height, 1u << i, s.filter_below}};
        dispatch(cmd, &e->atrous, sets[1 + i], &ap, sizeof ap, im->width, im->height);
    }
    return ROMA_SUCCESS;
}
