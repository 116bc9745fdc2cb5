#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vulkan/vk_internal.h"

struct roma_gpu_timer {
    roma_context *ctx;
    VkQueryPool pool;
    uint32_t max_scopes;
    uint32_t used;
    uint64_t valid_mask; /* timestampValidBits of the queue family */
    roma_gpu_timing *names;
    unsigned char *open; /* per scope: begun, not yet ended (a second end would rewrite its query) */
};

roma_result roma_gpu_timer_create(roma_context *ctx, uint32_t max_scopes, roma_gpu_timer **out)
{
    if (!out)
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gpu_timer_create: out_timer is NULL");
    *out = NULL;
    if (!ctx || max_scopes == 0 || max_scopes > 4096)
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gpu_timer_create: need a context and 1..4096 scopes (got %u)", max_scopes);
    roma_gpu_timer *t = calloc(1, sizeof *t);
    roma_gpu_timing *names = calloc(max_scopes, sizeof *names);
    unsigned char *open = calloc(max_scopes, 1);
    if (!t || !names || !open) {
        free(t);
        free(names);
        free(open);
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_gpu_timer_create: out of memory");
    }
    t->ctx = ctx;
    t->max_scopes = max_scopes;
    t->names = names;
    t->open = open;
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical_device, &family_count, NULL);
    VkQueueFamilyProperties *families = calloc(family_count ? family_count : 1, sizeof *families);
    uint32_t bits = 64;
    if (families) {
        vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical_device, &family_count, families);
        if (ctx->queue_family < family_count)
            bits = families[ctx->queue_family].timestampValidBits;
        free(families);
    }
    t->valid_mask = bits >= 64 ? UINT64_MAX : ((1ull << bits) - 1ull);
    VkQueryPoolCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_TIMESTAMP,
        .queryCount = 2 * max_scopes,
    };
    roma_result r = roma_vk_check(ctx, vkCreateQueryPool(ctx->device, &info, ctx->allocator, &t->pool), "vkCreateQueryPool");
    if (r != ROMA_SUCCESS) {
        roma_gpu_timer_destroy(t);
        return r;
    }
    /* Host reset so that reading before any use reports NOT_READY instead of undefined data. */
    vkResetQueryPool(ctx->device, t->pool, 0, 2 * max_scopes);
    *out = t;
    return ROMA_SUCCESS;
}

const roma_context *roma_gpu_timer_context(const roma_gpu_timer *t)
{
    return t ? t->ctx : NULL;
}

void roma_gpu_timer_destroy(roma_gpu_timer *t)
{
    if (!t)
        return;
    if (t->pool)
        vkDestroyQueryPool(t->ctx->device, t->pool, t->ctx->allocator);
    free(t->names);
    free(t->open);
    free(t);
}

void roma_gpu_timer_reset(roma_gpu_timer *t, VkCommandBuffer cmd)
{
    if (!t || !cmd)
        return;
    vkCmdResetQueryPool(cmd, t->pool, 0, 2 * t->max_scopes);
    t->used = 0;
    memset(t->open, 0, t->max_scopes);
}

uint32_t roma_gpu_timer_begin(roma_gpu_timer *t, VkCommandBuffer cmd, const char *name)
{
    if (!t || !cmd || t->used >= t->max_scopes)
        return UINT32_MAX;
    uint32_t scope = t->used++;
    snprintf(t->names[scope].name, sizeof t->names[scope].name, "%s", name ? name : "");
    t->names[scope].milliseconds = 0.0;
    t->open[scope] = 1;
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, t->pool, 2 * scope);
    return scope;
}

void roma_gpu_timer_end(roma_gpu_timer *t, VkCommandBuffer cmd, uint32_t scope)
{
    if (!t || !cmd || scope >= t->used || !t->open[scope])
        return;
    t->open[scope] = 0;
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, t->pool, 2 * scope + 1);
}

roma_result roma_gpu_timer_read(roma_gpu_timer *t, roma_gpu_timing *out, uint32_t *count)
{
    if (!t || !count || (!out && *count))
        return roma_fail(t ? &t->ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gpu_timer_read: %s", !t ? "timer is NULL" : !count ? "count is NULL"
                                                                          : "out_timings is NULL but *count is not 0");
    uint32_t n = *count < t->used ? *count : t->used;
    *count = t->used;
    if (n == 0)
        return ROMA_SUCCESS;
    uint64_t *ticks = calloc(2 * (size_t)n, sizeof *ticks);
    if (!ticks)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    VkResult vr = vkGetQueryPoolResults(t->ctx->device, t->pool, 0, 2 * n, 2 * n * sizeof(uint64_t),
                                        ticks, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    roma_result r = ROMA_SUCCESS;
    if (vr == VK_NOT_READY) {
        r = ROMA_ERROR_NOT_READY;
    } else if (vr != VK_SUCCESS) {
        r = roma_vk_check(t->ctx, vr, "vkGetQueryPoolResults");
    } else {
        double period_ms = (double)t->ctx->properties.limits.timestampPeriod * 1e-6;
        for (uint32_t i = 0; i < n; ++i) {
            uint64_t begin = ticks[2 * i] & t->valid_mask, end = ticks[2 * i + 1] & t->valid_mask;
            uint64_t delta = (end - begin) & t->valid_mask; /* wraps with the counter */
            out[i] = t->names[i];
            out[i].milliseconds = (double)delta * period_ms;
        }
    }
    free(ticks);
    return r;
}
