#include "passes/pixel_pass.h"
#include "study/study_shaders.h"

#include <string.h>

#include "roma_shared.h"

/* Earlier writes of the G-buffer (fragment/compute), the ROMA build (compute) and clears
 * (transfer) visible to the pass: to its storage accesses and to its texel fetches (the
 * G-buffer, the list and the BOM are uniform texel buffers: sampled reads). */
static void record_in_barrier(VkCommandBuffer cmd)
{
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_UNIFORM_READ_BIT);
}

/* The pass's writes visible to later compute passes, transfers and the host. */
static void record_out_barrier(VkCommandBuffer cmd)
{
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT |
                                VK_PIPELINE_STAGE_2_HOST_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
}

static const VkDescriptorType pixel_types[ROMA_PIXEL_BINDINGS] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,       VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER};

static void binding_release(roma_context *ctx, roma_pixel_binding *b)
{
    roma_descriptor_set_destroy(ctx, &b->set);
    if (b->gbuffer_view)
        vkDestroyBufferView(ctx->device, b->gbuffer_view, ctx->allocator);
    if (b->list_view)
        vkDestroyBufferView(ctx->device, b->list_view, ctx->allocator);
}

roma_result roma_pixel_pass_create(roma_context *ctx, const char *module, uint32_t push_size, int traces,
                                   roma_pixel_pass *out)
{
    return roma_pixel_pass_create_spec(ctx, module, push_size, traces, NULL, 0, out);
}

roma_result roma_pixel_pass_create_spec(roma_context *ctx, const char *module, uint32_t push_size, int traces,
                                        const uint32_t *constants, uint32_t constant_count, roma_pixel_pass *out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    memset(out, 0, sizeof *out);
    const uint32_t bindings = traces ? ROMA_PIXEL_BINDINGS : 0;
    roma_result r = roma_compute_pipeline_create_spec(ctx, module, pixel_types, bindings, push_size, constants,
                                                      constant_count, &out->pipeline);
    if (r != ROMA_SUCCESS)
        return r;
    out->ctx = ctx;
    out->name = module;
    out->push_size = push_size;
    out->binding_count = bindings;
    return ROMA_SUCCESS;
}

void roma_pixel_pass_destroy(roma_pixel_pass *pass)
{
    if (pass->ctx) {
        for (uint32_t i = 0; i < pass->set_count; ++i)
            binding_release(pass->ctx, &pass->sets[i]);
        roma_compute_pipeline_destroy(pass->ctx, &pass->pipeline);
    }
    memset(pass, 0, sizeof *pass);
}

/* The set of these buffers: found, or made and written once. */
static roma_result pass_set(roma_pixel_pass *pass, const roma_pixel_binding *key_in, VkDescriptorSet *out)
{
    for (uint32_t i = 0; i < pass->set_count; ++i) {
        const roma_pixel_binding *b = &pass->sets[i];
        if (b->maps == key_in->maps && b->params == key_in->params && b->gbuffer == key_in->gbuffer &&
            b->list == key_in->list && b->accum == key_in->accum && b->bom == key_in->bom) {
            *out = b->set.set;
            return ROMA_SUCCESS;
        }
    }
    if (pass->set_count == ROMA_PIXEL_PASS_MAX_SETS)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: recorded with more than %d combinations of map, G-buffer and buffers", pass->name,
                         ROMA_PIXEL_PASS_MAX_SETS);
    roma_context *ctx = pass->ctx;
    roma_pixel_binding key = *key_in;
    roma_result r = roma_buffer_view_create(ctx, key.gbuffer, VK_FORMAT_R32G32B32A32_SFLOAT, &key.gbuffer_view);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, key.list, VK_FORMAT_R32_UINT, &key.list_view);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create(ctx, &pass->pipeline, pixel_types, ROMA_PIXEL_BINDINGS, &key.set);
    if (r != ROMA_SUCCESS) {
        binding_release(ctx, &key);
        return r;
    }
    roma_descriptor_write_view(ctx, &key.set, ROMA_TRACE_BINDING_MAPS, pixel_types[ROMA_TRACE_BINDING_MAPS], key.maps);
    roma_descriptor_write_buffer(ctx, &key.set, ROMA_TRACE_BINDING_PARAMS, pixel_types[ROMA_TRACE_BINDING_PARAMS],
                                 key.params);
    const VkBufferView views[3] = {key.gbuffer_view, key.list_view, key.bom};
    const uint32_t view_bindings[3] = {ROMA_PIXEL_BINDING_GBUFFER, ROMA_PIXEL_BINDING_LIST, ROMA_PIXEL_BINDING_BOM};
    for (uint32_t b = 0; b < 3; ++b)
        roma_descriptor_write_view(ctx, &key.set, view_bindings[b], pixel_types[view_bindings[b]], views[b]);
    roma_descriptor_write_buffer(ctx, &key.set, ROMA_PIXEL_BINDING_ACCUM, pixel_types[ROMA_PIXEL_BINDING_ACCUM],
                                 key.accum);
    pass->sets[pass->set_count++] = key;
    *out = key.set.set;
    return ROMA_SUCCESS;
}

roma_result roma_pixel_pass_record(roma_pixel_pass *pass, VkCommandBuffer cmd, uint32_t width, uint32_t height,
                                   const void *push)
{
    if (!pass->ctx || !cmd || !push || pass->binding_count)
        return ROMA_ERROR_INVALID_ARGUMENT;
    uint32_t gx = (width + ROMA_PIXEL_WORKGROUP_X - 1) / ROMA_PIXEL_WORKGROUP_X;
    uint32_t gy = (height + ROMA_PIXEL_WORKGROUP_Y - 1) / ROMA_PIXEL_WORKGROUP_Y;
    if (width == 0 || height == 0 || gx > 65535u || gy > 65535u)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: image %ux%u is empty or too large",
                         pass->name, width, height);
    record_in_barrier(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.pipeline);
    vkCmdPushConstants(cmd, pass->pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass->push_size, push);
    vkCmdDispatch(cmd, gx, gy, 1);
    record_out_barrier(cmd);
    return ROMA_SUCCESS;
}

roma_result roma_pixel_pass_record_list(roma_pixel_pass *pass, VkCommandBuffer cmd, const roma_gbuffer_list *list,
                                        const roma_map_info *map, VkBufferView bom, VkBuffer gbuffer, VkBuffer accum,
                                        const void *push)
{
    if (!pass->ctx || !cmd || !push || !list || !list->buffer.buffer || !pass->binding_count || !map ||
        !map->maps_view || !bom || !gbuffer || !accum)
        return pass->ctx ? roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                                     "%s: list, map, BOM, G-buffer and accumulator are required", pass->name)
                         : ROMA_ERROR_INVALID_ARGUMENT;
    const roma_pixel_binding key = {map->maps_view, bom, map->params_buffer, gbuffer, list->buffer.buffer, accum,
                                    VK_NULL_HANDLE, VK_NULL_HANDLE, {0}};
    VkDescriptorSet set = VK_NULL_HANDLE;
    roma_result r = pass_set(pass, &key, &set);
    if (r != ROMA_SUCCESS)
        return r;
    record_in_barrier(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.layout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, pass->pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass->push_size, push);
    vkCmdDispatchIndirect(cmd, list->buffer.buffer, 0);
    record_out_barrier(cmd);
    return ROMA_SUCCESS;
}
