/* The loop budget of a shader invocation (loop_budget.h). */
#include "vulkan/loop_budget.h"

#include <string.h>

#include "roma_shared.h"
#include "vulkan/vk_internal.h"

uint32_t roma_loop_plan(const roma_context *ctx)
{
    return ctx ? ctx->loop_plan : UINT32_MAX;
}

uint32_t roma_loop_items_per_dispatch(const roma_context *ctx, uint32_t fixed, uint32_t per_item, uint32_t count)
{
    const uint32_t plan = roma_loop_plan(ctx);
    if (count <= 1 || plan == UINT32_MAX)
        return count;
    uint64_t room = plan > fixed ? plan - fixed : 0;
    uint64_t items = per_item ? room / per_item : count;
    return items < 1 ? 1 : items > count ? count : (uint32_t)items;
}

static uint32_t sat_add(uint64_t a, uint64_t b) { return a + b > UINT32_MAX ? UINT32_MAX : (uint32_t)(a + b); }

roma_loop_parts roma_loop_parts_plan(const roma_context *ctx, uint32_t fixed, uint32_t count, uint32_t per_item,
                                     uint32_t sub_count, uint32_t per_sub)
{
    roma_loop_parts p = {count, sub_count, count ? count : 1, sub_count ? sub_count : 1};
    const uint64_t whole_item = (uint64_t)per_item + (uint64_t)sub_count * per_sub;
    const uint32_t plan = roma_loop_plan(ctx);
    if (plan == UINT32_MAX)
        return p;
    if ((uint64_t)fixed + whole_item <= plan) {
        p.per_part = roma_loop_items_per_dispatch(ctx, fixed, sat_add(whole_item, 0), count);
    } else {
        p.per_part = 1; /* one item a part, its sub-items split */
        p.sub_per_part = roma_loop_items_per_dispatch(ctx, sat_add(fixed, per_item), per_sub, sub_count);
    }
    if (!p.per_part)
        p.per_part = 1;
    if (!p.sub_per_part)
        p.sub_per_part = 1;
    return p;
}

int roma_loop_parts_get(const roma_loop_parts *p, uint32_t i, uint32_t range[4])
{
    const uint32_t items = p->count ? (p->count - 1) / p->per_part + 1 : 1;
    const uint32_t subs = p->sub_count ? (p->sub_count - 1) / p->sub_per_part + 1 : 1;
    if ((uint64_t)i >= (uint64_t)items * subs)
        return 0;
    const uint32_t a = i / subs, b = i % subs;
    range[0] = a * p->per_part;
    range[1] = p->count - range[0] > p->per_part ? range[0] + p->per_part : p->count;
    range[2] = b * p->sub_per_part;
    range[3] = p->sub_count - range[2] > p->sub_per_part ? range[2] + p->sub_per_part : p->sub_count;
    return 1;
}

roma_result roma_loop_probe(roma_context *ctx, uint32_t iterations, uint32_t *out_ran)
{
    if (out_ran)
        *out_ran = 0;
    if (!ctx || !out_ran)
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_loop_probe: %s is NULL",
                         ctx ? "out_ran" : "context");
    roma_compute_pipeline pipe;
    roma_buffer buffer = {0};
    roma_descriptor_set set = {0};
    const VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    roma_result r = roma_compute_pipeline_create(ctx, "loop_probe.comp", 1, sizeof(roma_fill_push), &pipe);
    if (r != ROMA_SUCCESS)
        return r;
    r = roma_buffer_create(ctx, 2 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, ROMA_MEMORY_READBACK,
                           &buffer);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create(ctx, &pipe, &type, 1, &set);
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS) {
        roma_descriptor_write_buffer(ctx, &set, ROMA_FILL_BINDING_OUTPUT, type, buffer.buffer);
        r = roma_begin_one_shot(ctx, &cmd);
    }
    if (r == ROMA_SUCCESS) {
        const roma_fill_push push = {.count = iterations, .value = 1u};
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.layout, 0, 1, &set.set, 0, NULL);
        vkCmdPushConstants(cmd, pipe.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        vkCmdDispatch(cmd, 1, 1, 1);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        r = roma_submit_one_shot(ctx, cmd);
    }
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(ctx, &buffer);
    if (r == ROMA_SUCCESS)
        *out_ran = ((const uint32_t *)buffer.mapped)[0];
    roma_descriptor_set_destroy(ctx, &set);
    roma_buffer_destroy(ctx, &buffer);
    roma_compute_pipeline_destroy(ctx, &pipe);
    return r;
}
