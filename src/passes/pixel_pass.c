#include "passes/pixel_pass.h"

#include <string.h>

#include "roma_shared.h"

/* Earlier writes of the G-buffer (fragment/compute), the ROMA build (compute) and clears
 * (transfer) visible to the pass. */
static void record_in_barrier(VkCommandBuffer cmd)
{
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
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

roma_result roma_pixel_pass_create(roma_context *ctx, const char *module, uint32_t push_size, int traces,
                                   roma_pixel_pass *out)
{
    return roma_pixel_pass_create_bound(ctx, module, push_size, roma_trace_binding_types,
                                        traces ? ROMA_TRACE_BINDINGS : 0, out);
}

roma_result roma_pixel_pass_create_bound(roma_context *ctx, const char *module, uint32_t push_size,
                                         const VkDescriptorType *types, uint32_t binding_count,
                                         roma_pixel_pass *out)
{
    memset(out, 0, sizeof *out);
    roma_result r = roma_compute_pipeline_create_typed(ctx, module, types, binding_count, push_size, &out->pipeline);
    if (r != ROMA_SUCCESS)
        return r;
    out->ctx = ctx;
    out->name = module;
    out->push_size = push_size;
    out->binding_count = binding_count;
    return ROMA_SUCCESS;
}

void roma_pixel_pass_destroy(roma_pixel_pass *pass)
{
    if (pass->ctx)
        roma_compute_pipeline_destroy(pass->ctx, &pass->pipeline);
    memset(pass, 0, sizeof *pass);
}

roma_result roma_pixel_pass_record(roma_pixel_pass *pass, VkCommandBuffer cmd, uint32_t width, uint32_t height,
                                   VkDescriptorSet trace_set, const void *push)
{
    if (!pass->ctx || !cmd || !push || (pass->binding_count && !trace_set))
        return ROMA_ERROR_INVALID_ARGUMENT;
    uint32_t gx = (width + ROMA_PIXEL_WORKGROUP_X - 1) / ROMA_PIXEL_WORKGROUP_X;
    uint32_t gy = (height + ROMA_PIXEL_WORKGROUP_Y - 1) / ROMA_PIXEL_WORKGROUP_Y;
    if (width == 0 || height == 0 || gx > 65535u || gy > 65535u)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: image %ux%u is empty or too large",
                         pass->name, width, height);
    record_in_barrier(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.pipeline);
    if (pass->binding_count)
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.layout, 0, 1, &trace_set, 0,
                                NULL);
    vkCmdPushConstants(cmd, pass->pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass->push_size, push);
    vkCmdDispatch(cmd, gx, gy, 1);
    record_out_barrier(cmd);
    return ROMA_SUCCESS;
}

roma_result roma_pixel_pass_record_list(roma_pixel_pass *pass, VkCommandBuffer cmd, const roma_pixel_list *list,
                                        VkDescriptorSet trace_set, const void *push)
{
    if (!pass->ctx || !cmd || !push || !list || !list->buffer.buffer || (pass->binding_count && !trace_set))
        return ROMA_ERROR_INVALID_ARGUMENT;
    record_in_barrier(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.pipeline);
    if (pass->binding_count)
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.layout, 0, 1, &trace_set, 0,
                                NULL);
    vkCmdPushConstants(cmd, pass->pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass->push_size, push);
    vkCmdDispatchIndirect(cmd, list->buffer.buffer, 0);
    record_out_barrier(cmd);
    return ROMA_SUCCESS;
}
