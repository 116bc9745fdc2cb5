#include <string.h>

#include "vulkan/shader_table.h"
#include "vulkan/vk_internal.h"

const char *roma_vk_result_string(VkResult vr)
{
    switch (vr) {
#define CASE(x) case x: return #x;
    CASE(VK_SUCCESS) CASE(VK_NOT_READY) CASE(VK_TIMEOUT) CASE(VK_INCOMPLETE)
    CASE(VK_ERROR_OUT_OF_HOST_MEMORY) CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    CASE(VK_ERROR_INITIALIZATION_FAILED) CASE(VK_ERROR_DEVICE_LOST)
    CASE(VK_ERROR_MEMORY_MAP_FAILED) CASE(VK_ERROR_LAYER_NOT_PRESENT)
    CASE(VK_ERROR_EXTENSION_NOT_PRESENT) CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    CASE(VK_ERROR_INCOMPATIBLE_DRIVER) CASE(VK_ERROR_TOO_MANY_OBJECTS)
    CASE(VK_ERROR_FORMAT_NOT_SUPPORTED) CASE(VK_ERROR_FRAGMENTED_POOL)
    CASE(VK_ERROR_OUT_OF_POOL_MEMORY) CASE(VK_ERROR_UNKNOWN)
#undef CASE
    default: return "VkResult (other)";
    }
}

roma_result roma_vk_check(const roma_context *ctx, VkResult vr, const char *what)
{
    if (vr == VK_SUCCESS)
        return ROMA_SUCCESS;
    roma_result r;
    switch (vr) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: r = ROMA_ERROR_OUT_OF_HOST_MEMORY; break;
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: r = ROMA_ERROR_OUT_OF_DEVICE_MEMORY; break;
    case VK_ERROR_DEVICE_LOST: r = ROMA_ERROR_DEVICE_LOST; break;
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_LAYER_NOT_PRESENT: r = ROMA_ERROR_MISSING_FEATURE; break;
    default: r = ROMA_ERROR_VULKAN; break;
    }
    return roma_fail(ctx ? &ctx->logger : NULL, r, "%s failed: %s", what, roma_vk_result_string(vr));
}

static uint32_t find_memory_type(const roma_context *ctx, uint32_t type_bits, VkMemoryPropertyFlags want,
                                 VkMemoryPropertyFlags prefer)
{
    const VkPhysicalDeviceMemoryProperties *mp = &ctx->memory_properties;
    for (int pass = 0; pass < 2; ++pass) {
        VkMemoryPropertyFlags need = pass == 0 ? (want | prefer) : want;
        for (uint32_t i = 0; i < mp->memoryTypeCount; ++i)
            if ((type_bits & (1u << i)) && (mp->memoryTypes[i].propertyFlags & need) == need)
                return i;
    }
    return UINT32_MAX;
}

roma_result roma_device_memory_reserve(roma_context *ctx, VkDeviceSize bytes, const char *what)
{
    if (ctx->max_allocation_size && bytes > ctx->max_allocation_size)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_DEVICE_MEMORY,
                         "%s: %llu bytes in one allocation, the device allows at most %llu", what,
                         (unsigned long long)bytes, (unsigned long long)ctx->max_allocation_size);
    roma_mutex_lock(&ctx->memory_lock);
    const uint64_t in_use = ctx->memory_in_use;
    const int over = ctx->memory_budget && bytes > ctx->memory_budget - in_use;
    if (!over)
        ctx->memory_in_use += bytes;
    roma_mutex_unlock(&ctx->memory_lock);
    if (over)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_DEVICE_MEMORY,
                         "%s: %llu more bytes of device memory would exceed the context's budget of %llu "
                         "(%llu in use)", what, (unsigned long long)bytes,
                         (unsigned long long)ctx->memory_budget, (unsigned long long)in_use);
    return ROMA_SUCCESS;
}

void roma_device_memory_release(roma_context *ctx, VkDeviceSize bytes)
{
    roma_mutex_lock(&ctx->memory_lock);
    ctx->memory_in_use -= bytes < ctx->memory_in_use ? bytes : ctx->memory_in_use;
    roma_mutex_unlock(&ctx->memory_lock);
}

roma_result roma_buffer_create(roma_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                               roma_memory_kind kind, roma_buffer *out)
{
    memset(out, 0, sizeof *out);
    if (size == 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "buffer of size 0");
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    roma_result r = roma_vk_check(ctx, vkCreateBuffer(ctx->device, &info, ctx->allocator, &out->buffer), "vkCreateBuffer");
    if (r != ROMA_SUCCESS)
        return r;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx->device, out->buffer, &req);
    VkMemoryPropertyFlags want = 0, prefer = 0;
    switch (kind) {
    case ROMA_MEMORY_DEVICE: want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case ROMA_MEMORY_UPLOAD:
        want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        break;
    case ROMA_MEMORY_READBACK:
        want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
        prefer = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        break;
    case ROMA_MEMORY_DEVICE_MAPPED:
        want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
               VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        if (ctx->force_staging)
            kind = ROMA_MEMORY_DEVICE, want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        break;
    }
    uint32_t type = find_memory_type(ctx, req.memoryTypeBits, want, prefer);
    if (type == UINT32_MAX && kind == ROMA_MEMORY_DEVICE_MAPPED)
        type = find_memory_type(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    if (type == UINT32_MAX && kind == ROMA_MEMORY_DEVICE)
        type = find_memory_type(ctx, req.memoryTypeBits, 0, 0);
    if (type == UINT32_MAX) {
        roma_buffer_destroy(ctx, out);
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE, "no memory type for a buffer of %llu bytes",
                         (unsigned long long)size);
    }
    VkMemoryAllocateFlagsInfo flags = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
        .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT,
    };
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .pNext = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) ? &flags : NULL,
        .allocationSize = req.size,
        .memoryTypeIndex = type,
    };
    r = roma_device_memory_reserve(ctx, req.size, "buffer");
    if (r != ROMA_SUCCESS) {
        roma_buffer_destroy(ctx, out);
        return r;
    }
    out->allocated = req.size;
    VkResult vr = vkAllocateMemory(ctx->device, &alloc, ctx->allocator, &out->memory);
    if (vr == VK_SUCCESS)
        vr = vkBindBufferMemory(ctx->device, out->buffer, out->memory, 0);
    out->memory_flags = ctx->memory_properties.memoryTypes[type].propertyFlags;
    if (vr == VK_SUCCESS && kind != ROMA_MEMORY_DEVICE &&
        (out->memory_flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT))
        vr = vkMapMemory(ctx->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped);
    if (vr != VK_SUCCESS) {
        roma_buffer_destroy(ctx, out);
        return roma_vk_check(ctx, vr, "allocating buffer memory");
    }
    out->size = size;
    if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) {
        VkBufferDeviceAddressInfo info_addr = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO,
            .buffer = out->buffer,
        };
        out->address = vkGetBufferDeviceAddress(ctx->device, &info_addr);
    }
    return ROMA_SUCCESS;
}

void roma_buffer_destroy(roma_context *ctx, roma_buffer *b)
{
    if (!ctx || !b)
        return;
    if (b->buffer)
        vkDestroyBuffer(ctx->device, b->buffer, ctx->allocator);
    if (b->memory)
        vkFreeMemory(ctx->device, b->memory, ctx->allocator); /* unmaps implicitly */
    roma_device_memory_release(ctx, b->allocated);
    memset(b, 0, sizeof *b);
}

roma_result roma_buffer_invalidate(roma_context *ctx, const roma_buffer *b)
{
    VkMappedMemoryRange range = {
        .sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
        .memory = b->memory,
        .offset = 0,
        .size = VK_WHOLE_SIZE,
    };
    return roma_vk_check(ctx, vkInvalidateMappedMemoryRanges(ctx->device, 1, &range),
                         "vkInvalidateMappedMemoryRanges");
}

void roma_cmd_memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                             VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = src_stage,
        .srcAccessMask = src_access,
        .dstStageMask = dst_stage,
        .dstAccessMask = dst_access,
    };
    VkDependencyInfo dep = {
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .memoryBarrierCount = 1,
        .pMemoryBarriers = &barrier,
    };
    vkCmdPipelineBarrier2(cmd, &dep);
}

roma_result roma_begin_one_shot(roma_context *ctx, VkCommandBuffer *out_cmd)
{
    *out_cmd = VK_NULL_HANDLE;
    roma_mutex_lock(&ctx->submit_lock); /* the pool until roma_submit_one_shot */
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = ctx->command_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    roma_result r = roma_vk_check(ctx, vkAllocateCommandBuffers(ctx->device, &alloc, out_cmd),
                                  "vkAllocateCommandBuffers");
    if (r != ROMA_SUCCESS) {
        roma_mutex_unlock(&ctx->submit_lock);
        return r;
    }
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    r = roma_vk_check(ctx, vkBeginCommandBuffer(*out_cmd, &begin), "vkBeginCommandBuffer");
    if (r != ROMA_SUCCESS) {
        vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, out_cmd);
        *out_cmd = VK_NULL_HANDLE;
        roma_mutex_unlock(&ctx->submit_lock);
    }
    return r;
}

roma_result roma_submit_one_shot(roma_context *ctx, VkCommandBuffer cmd)
{
    roma_result r = roma_vk_check(ctx, vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    if (r == ROMA_SUCCESS) {
        VkSubmitInfo submit = {
            .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
            .commandBufferCount = 1,
            .pCommandBuffers = &cmd,
        };
        if (ctx->queue_lock.fn)
            ctx->queue_lock.fn(1, ctx->queue_lock.user_data);
        r = roma_vk_check(ctx, vkQueueSubmit(ctx->queue, 1, &submit, ctx->fence), "vkQueueSubmit");
        if (ctx->queue_lock.fn)
            ctx->queue_lock.fn(0, ctx->queue_lock.user_data);
        ++ctx->queue_submits;
        if (r == ROMA_SUCCESS) {
            ++ctx->queue_waits;
            r = roma_vk_check(ctx, vkWaitForFences(ctx->device, 1, &ctx->fence, VK_TRUE, UINT64_MAX),
                              "vkWaitForFences");
            vkResetFences(ctx->device, 1, &ctx->fence);
        }
    }
    vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &cmd);
    roma_mutex_unlock(&ctx->submit_lock);
    return r;
}

const roma_spirv_module *roma_find_spirv(const roma_context *ctx, const char *name)
{
    for (const roma_spirv_module *m = roma_spirv_modules; m->name; ++m)
        if (strcmp(m->name, name) == 0)
            return m;
    for (const roma_spirv_module *m = ctx->study_modules; m && m->name; ++m)
        if (strcmp(m->name, name) == 0)
            return m;
    return NULL;
}

void roma_cmd_dispatch_linear(VkCommandBuffer cmd, uint64_t invocations, uint32_t group_size)
{
    uint64_t groups = (invocations + group_size - 1) / group_size;
    if (groups == 0)
        return;
    uint32_t x = groups < 65535u ? (uint32_t)groups : 65535u;
    uint32_t y = (uint32_t)((groups + x - 1) / x);
    vkCmdDispatch(cmd, x, y, 1);
}
