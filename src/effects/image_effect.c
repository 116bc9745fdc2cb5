/* The shared part of the public effects on G-buffer images (image_effect.h). */
#include "effects/image_effect.h"

#include <string.h>

#include "effects/pixel_list_internal.h"
#include "map/map_internal.h"
#include "roma_shared.h"
#include "util/log.h"

roma_result roma_nearest_sampler_create(roma_context *ctx, VkSampler *out)
{
    VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                              .magFilter = VK_FILTER_NEAREST,
                              .minFilter = VK_FILTER_NEAREST,
                              .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    return roma_vk_check(ctx, vkCreateSampler(ctx->device, &si, ctx->allocator, out), "vkCreateSampler");
}

roma_result roma_image_effect_init(roma_image_effect *e, roma_context *ctx, const roma_logger *log, const char *name,
                                   const char *module, const char *list_module, float background, uint32_t inputs,
                                   uint32_t push_size, uint32_t frames_in_flight, roma_pixel_dispatch dispatch)
{
    const uint32_t outputs = 1;
    memset(e, 0, sizeof *e);
    if ((unsigned)dispatch > ROMA_PIXEL_DISPATCH_EVERY_PIXEL) /* name: "roma_<effect>_record" */
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "%.*s_create: pixel_dispatch %d is not a roma_pixel_dispatch",
                         (int)(strlen(name) - strlen("_record")), name, (int)dispatch);
    e->ctx = ctx;
    e->logger = *log;
    e->name = name;
    e->module = module;
    e->inputs = inputs;
    e->outputs = outputs;
    e->push_size = push_size;
    e->list_module = list_module;
    /* The upsample writes the list pass's output format. */
    e->upsample_module = strstr(list_module, "rgba32f") ? "image_upsample_rgba32f.comp" : "image_upsample_r32f.comp";
    e->listed = dispatch == ROMA_PIXEL_DISPATCH_LIST ||
                (dispatch == ROMA_PIXEL_DISPATCH_AUTO && ctx->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
    for (int i = 0; i < 4; ++i)
        e->background[i] = background;
    VkDescriptorType types[ROMA_IMAGE_EFFECT_MAX_IMAGES + 2];
    for (uint32_t i = 0; i < inputs + outputs; ++i)
        types[i] = i < inputs ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    types[inputs + outputs] = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER; /* the map's BOM (bom_view) */
    types[inputs + outputs + 1] = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;   /* the covered-pixel list */
    roma_result r = roma_nearest_sampler_create(ctx, &e->sampler);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, roma_trace_binding_types, ROMA_TRACE_BINDINGS, &e->trace_layout);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, types, inputs + outputs + 2, &e->images_layout);
    if (r == ROMA_SUCCESS) {
        VkDescriptorSetLayout sets[2] = {e->trace_layout, e->images_layout};
        VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size};
        VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                         .setLayoutCount = 2,
                                         .pSetLayouts = sets,
                                         .pushConstantRangeCount = 1,
                                         .pPushConstantRanges = &push};
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &li, ctx->allocator, &e->layout),
                          "vkCreatePipelineLayout");
    }
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_make(ctx, module, e->layout, &(uint32_t){(uint32_t)e->listed}, 1,
                                       &e->pipelines[e->listed][0]);
    if (r == ROMA_SUCCESS && e->listed)
        r = roma_compute_pipeline_make(ctx, list_module, e->layout, NULL, 0, &e->list_pipeline);
    const VkDescriptorPoolSize sizes[4] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, inputs},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, outputs},
                                           {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_init(&e->sets, ctx, frames_in_flight, ROMA_IMAGE_EFFECT_RECORDS_PER_SLOT, 1, sizes, 4);
    if (r != ROMA_SUCCESS)
        roma_image_effect_free(e);
    return r;
}

void roma_image_effect_free(roma_image_effect *e)
{
    if (!e->ctx)
        return;
    VkDevice dev = e->ctx->device;
    const VkAllocationCallbacks *a = e->ctx->allocator;
    roma_slot_sets_free(&e->sets);
    roma_covered_lists_free(&e->lists, e->ctx);
    if (e->list_pipeline)
        vkDestroyPipeline(dev, e->list_pipeline, a);
    if (e->upsample_pipeline)
        vkDestroyPipeline(dev, e->upsample_pipeline, a);
    for (int listed = 0; listed < 2; ++listed)
        for (int cascaded = 0; cascaded < 2; ++cascaded)
            if (e->pipelines[listed][cascaded])
                vkDestroyPipeline(dev, e->pipelines[listed][cascaded], a);
    if (e->layout)
        vkDestroyPipelineLayout(dev, e->layout, a);
    if (e->images_layout)
        vkDestroyDescriptorSetLayout(dev, e->images_layout, a);
    if (e->trace_layout)
        vkDestroyDescriptorSetLayout(dev, e->trace_layout, a);
    if (e->sampler)
        vkDestroySampler(dev, e->sampler, a);
    memset(e, 0, sizeof *e);
}

int roma_image_effect_divisor_valid(uint32_t resolution_divisor)
{
    return resolution_divisor <= 2 || resolution_divisor == 4;
}

/* The traced pixel's place in an s x s block in frame n: every place once in s * s frames,
 * in the order of a Bayer matrix, so that consecutive frames trace far-apart places. */
static void block_place(uint32_t scale, uint32_t frame, uint32_t place[2])
{
    static const uint8_t order2[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    static const uint8_t order4[16][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                          {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};
    const uint8_t *p = scale == 4 ? order4[frame % 16] : scale == 2 ? order2[frame % 4] : (const uint8_t[2]){0, 0};
    place[0] = p[0];
    place[1] = p[1];
}

roma_result roma_image_effect_begin(roma_image_effect *e, uint32_t slot, uint32_t frame, const roma_map *map,
                                    const roma_pixel_list *pixels, uint32_t width, uint32_t height,
                                    uint32_t resolution_divisor, roma_map_info *info)
{
    if (slot >= e->sets.frames_in_flight)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: slot %u of %u", e->name, slot,
                         e->sets.frames_in_flight);
    roma_result r = roma_map_get_info(map, info);
    if (r != ROMA_SUCCESS)
        return r;
    if (!map->built)
        return roma_fail(&e->logger, ROMA_ERROR_NOT_READY, "%s: record a build of the map first", e->name);
    VkBuffer shared = VK_NULL_HANDLE;
    if (pixels) {
        r = roma_pixel_list_slot_buffer(pixels, e->ctx, &e->logger, e->name, slot, width, height, &shared);
        if (r != ROMA_SUCCESS)
            return r;
    }
    /* A map of several cascade levels needs the cascade code, a shared list or a resolution
     * divisor the listed variant (the divisor's list: the traced pixels), a divisor the list
     * and upsample passes (made once, before anything of the record is recorded). */
    const uint32_t scale = resolution_divisor > 1 ? resolution_divisor : 1;
    /* At a divisor the effect lists one pixel a block itself, listed or not (roma_image_effect_
     * check_size took only a listed effect's list). */
    const uint64_t blocks = (uint64_t)((width + scale - 1) / scale) * ((height + scale - 1) / scale);
    if (scale > 1 && sizeof(roma_pixel_list_header) + 4 * blocks > e->ctx->properties.limits.maxStorageBufferRange)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: the list of %ux%u pixels' blocks at resolution divisor %u exceeds maxStorageBufferRange",
                         e->name, width, height, scale);
    const int listed = shared || scale > 1 ? 1 : e->listed, cascaded = info->levels > 1;
    if (!e->pipelines[listed][cascaded]) {
        r = roma_compute_pipeline_make_flags(e->ctx, e->module, e->layout, &(uint32_t){(uint32_t)listed}, 1,
                                             cascaded ? ROMA_PIPELINE_CASCADES : 0, &e->pipelines[listed][cascaded]);
        if (r != ROMA_SUCCESS)
            return r;
    }
    if (scale > 1 && !e->list_pipeline) {
        r = roma_compute_pipeline_make(e->ctx, e->list_module, e->layout, NULL, 0, &e->list_pipeline);
        if (r != ROMA_SUCCESS)
            return r;
    }
    if (scale > 1 && !e->upsample_pipeline) {
        r = roma_compute_pipeline_make(e->ctx, e->upsample_module, e->layout, NULL, 0, &e->upsample_pipeline);
        if (r != ROMA_SUCCESS)
            return r;
    }
    e->traced = e->pipelines[listed][cascaded];
    e->given_list = shared != VK_NULL_HANDLE;
    e->shared_list = scale > 1 ? VK_NULL_HANDLE : shared; /* scaled: the traced pixels' own list */
    e->scale = scale;
    e->own_entries = scale > 1 || e->listed ? blocks : 0; /* its own list's; 0: a buffer never read */
    block_place(scale, frame, e->place);
    e->frame = frame;
    return ROMA_SUCCESS;
}

roma_result roma_image_effect_check_size(const roma_image_effect *e, const char *name, uint32_t width,
                                         uint32_t height)
{
    const uint32_t most = 65536u; /* the list holds (y << 16) | x (roma_image_list.glsl) */
    if (width > most || height > most)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: images of %ux%u, at most %u along each axis",
                         name, width, height, most);
    const uint64_t list_bytes = sizeof(roma_pixel_list_header) + 4ull * width * height;
    if (e->listed && list_bytes > e->ctx->properties.limits.maxStorageBufferRange)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: the covered-pixel list of %ux%u pixels (%llu bytes) exceeds maxStorageBufferRange (%u)",
                         name, width, height, (unsigned long long)list_bytes,
                         e->ctx->properties.limits.maxStorageBufferRange);
    return ROMA_SUCCESS;
}

int roma_image_effect_same_frame(const roma_image_effect *e, uint32_t slot)
{
    return roma_slot_sets_same_frame(&e->sets, slot, e->frame);
}

/* The list of the position image, then the effect's indirect dispatch over it. */
static void record_listed_dispatch(roma_image_effect *e, VkCommandBuffer cmd, const roma_buffer *list,
                                   const void *push, uint32_t width, uint32_t height)
{
    /* Scaled: one invocation per block lists its traced pixel (the upsample writes the rest). */
    const uint32_t s = e->scale, blocks_x = (width + s - 1) / s, blocks_y = (height + s - 1) / s;
    roma_image_list_push lp = {.config = {width, height, 0, s | e->place[0] << 8 | e->place[1] << 16}};
    memcpy(lp.background, e->background, sizeof lp.background);
    roma_covered_list_record(cmd, list->buffer, e->list_pipeline, e->layout, lp, (blocks_x + 7) / 8,
                             (blocks_y + 7) / 8);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->traced);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, e->push_size, push);
    vkCmdDispatchIndirect(cmd, list->buffer, 0);
}

roma_result roma_image_effect_dispatch(roma_image_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                       const roma_map_info *info, const VkImageView *views, VkImageLayout input_layout,
                                       const void *push, uint32_t width, uint32_t height)
{
    int same_frame = roma_image_effect_same_frame(e, slot);
    roma_result r = roma_slot_sets_begin(&e->sets, &e->logger, e->name, slot, e->frame);
    const int own = e->own_entries > 0;
    if (r == ROMA_SUCCESS && !e->shared_list)
        r = roma_covered_lists_reserve(&e->lists, e->ctx, &e->logger, e->name, slot, same_frame, e->own_entries);
    VkImageLayout in_layouts[ROMA_IMAGE_EFFECT_MAX_IMAGES];
    for (uint32_t i = 0; i < e->inputs; ++i)
        in_layouts[i] = input_layout ? input_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkDescriptorSet set = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_write_images(&e->sets, slot, e->images_layout, e->sampler, views, in_layouts, e->inputs,
                                        e->inputs + e->outputs, &set);
    if (r != ROMA_SUCCESS)
        return r;
    roma_slot_sets_commit(&e->sets, slot);
    const roma_buffer *list = &e->lists.lists[slot];
    VkDescriptorBufferInfo list_info = {e->shared_list ? e->shared_list : list->buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet writes[2] = {{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                       .dstSet = set,
                                       .dstBinding = e->inputs + e->outputs,
                                       .descriptorCount = 1,
                                       .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                                       .pTexelBufferView = &info->bom_view},
                                      {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                       .dstSet = set,
                                       .dstBinding = e->inputs + e->outputs + 1,
                                       .descriptorCount = 1,
                                       .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                       .pBufferInfo = &list_info}};
    vkUpdateDescriptorSets(e->ctx->device, 2, writes, 0, NULL);
    VkDescriptorSet sets[2] = {info->trace_set, set};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->layout, 0, 2, sets, 0, NULL);
    e->last_list = e->shared_list ? e->shared_list : own ? list->buffer : VK_NULL_HANDLE;
    e->last_groups[0] = (width + 7) / 8;
    e->last_groups[1] = (height + 7) / 8;
    if (e->shared_list) { /* listed once for the frame: roma_pixel_list_record's barrier made it visible */
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->traced);
        vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, e->push_size, push);
        vkCmdDispatchIndirect(cmd, e->shared_list, 0);
        return ROMA_SUCCESS;
    }
    if (own) {
        record_listed_dispatch(e, cmd, list, push, width, height);
        return ROMA_SUCCESS;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->traced);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, e->push_size, push);
    vkCmdDispatch(cmd, e->last_groups[0], e->last_groups[1], 1);
    return ROMA_SUCCESS;
}

void roma_image_effect_dispatch_more(roma_image_effect *e, VkCommandBuffer cmd, const void *push)
{
    /* The output the last part wrote, read and written by this one. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, e->push_size, push);
    if (e->last_list)
        vkCmdDispatchIndirect(cmd, e->last_list, 0);
    else
        vkCmdDispatch(cmd, e->last_groups[0], e->last_groups[1], 1);
}

void roma_image_effect_finish(roma_image_effect *e, VkCommandBuffer cmd, uint32_t width, uint32_t height)
{
    if (e->scale <= 1)
        return;
    /* The traced pixels' values, read here beside the pixels this pass writes. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_image_list_push up = {
        .config = {width, height, e->given_list ? 1u : 0u, e->scale | e->place[0] << 8 | e->place[1] << 16}};
    memcpy(up.background, e->background, sizeof up.background);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->upsample_pipeline);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof up, &up);
    vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
}
