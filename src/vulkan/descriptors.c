/* Descriptor sets for the passes that bind their buffers instead of reaching them by
 * address: on some devices (CPU implementations in particular) descriptor-based and
 * texel-buffer loads are much cheaper than buffer-device-address loads. */
#include <string.h>

#include "vulkan/vk_internal.h"

#define MAX_BINDINGS 16

const VkDescriptorType roma_trace_binding_types[2] = {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                                                      VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};

static roma_result set_create(roma_context *ctx, VkDescriptorSetLayout layout, const VkDescriptorType *types,
                              uint32_t binding_count, roma_descriptor_set *out);

roma_result roma_descriptor_layout_create(roma_context *ctx, const VkDescriptorType *types, uint32_t binding_count,
                                          VkDescriptorSetLayout *out)
{
    *out = VK_NULL_HANDLE;
    if (binding_count > MAX_BINDINGS)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "descriptor set layout: %u bindings",
                         binding_count);
    VkDescriptorSetLayoutBinding bindings[MAX_BINDINGS];
    for (uint32_t i = 0; i < binding_count; ++i)
        bindings[i] = (VkDescriptorSetLayoutBinding){i, types[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL};
    VkDescriptorSetLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = binding_count,
        .pBindings = bindings,
    };
    return roma_vk_check(ctx, vkCreateDescriptorSetLayout(ctx->device, &info, ctx->allocator, out),
                         "vkCreateDescriptorSetLayout");
}

roma_result roma_descriptor_set_create(roma_context *ctx, const roma_compute_pipeline *pipeline,
                                       const VkDescriptorType *types, uint32_t binding_count,
                                       roma_descriptor_set *out)
{
    memset(out, 0, sizeof *out);
    roma_result r = set_create(ctx, pipeline->set_layout, types, binding_count, out);
    if (r != ROMA_SUCCESS)
        roma_descriptor_set_destroy(ctx, out);
    return r;
}

roma_result roma_descriptor_set_create_with_layout(roma_context *ctx, const VkDescriptorType *types,
                                                   uint32_t binding_count, roma_descriptor_set *out)
{
    memset(out, 0, sizeof *out);
    if (binding_count == 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_descriptor_set_create: no bindings");
    roma_result r = roma_descriptor_layout_create(ctx, types, binding_count, &out->layout);
    if (r == ROMA_SUCCESS)
        r = set_create(ctx, out->layout, types, binding_count, out);
    if (r != ROMA_SUCCESS)
        roma_descriptor_set_destroy(ctx, out);
    return r;
}

static roma_result set_create(roma_context *ctx, VkDescriptorSetLayout layout, const VkDescriptorType *types,
                              uint32_t binding_count, roma_descriptor_set *out)
{
    if (binding_count == 0 || binding_count > MAX_BINDINGS)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_descriptor_set_create: %u bindings",
                         binding_count);
    VkDescriptorPoolSize sizes[MAX_BINDINGS];
    for (uint32_t i = 0; i < binding_count; ++i)
        sizes[i] = (VkDescriptorPoolSize){types[i], 1};
    VkDescriptorPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = binding_count,
        .pPoolSizes = sizes,
    };
    roma_result r = roma_vk_check(ctx, vkCreateDescriptorPool(ctx->device, &pool_info, ctx->allocator, &out->pool),
                                  "vkCreateDescriptorPool");
    if (r == ROMA_SUCCESS) {
        VkDescriptorSetAllocateInfo alloc = {
            .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
            .descriptorPool = out->pool,
            .descriptorSetCount = 1,
            .pSetLayouts = &layout,
        };
        r = roma_vk_check(ctx, vkAllocateDescriptorSets(ctx->device, &alloc, &out->set), "vkAllocateDescriptorSets");
    }
    return r;
}

void roma_descriptor_set_destroy(roma_context *ctx, roma_descriptor_set *set)
{
    if (!ctx || !set)
        return;
    if (set->pool)
        vkDestroyDescriptorPool(ctx->device, set->pool, ctx->allocator); /* frees the set */
    if (set->layout)
        vkDestroyDescriptorSetLayout(ctx->device, set->layout, ctx->allocator);
    memset(set, 0, sizeof *set);
}

/* One descriptor at binding: a buffer range or a texel-buffer view. */
static void write_one(roma_context *ctx, roma_descriptor_set *set, uint32_t binding, VkDescriptorType type,
                      const VkDescriptorBufferInfo *buffer, const VkBufferView *view)
{
    VkWriteDescriptorSet write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = set->set,
        .dstBinding = binding,
        .descriptorCount = 1,
        .descriptorType = type,
        .pBufferInfo = buffer,
        .pTexelBufferView = view,
    };
    vkUpdateDescriptorSets(ctx->device, 1, &write, 0, NULL);
}

void roma_descriptor_write_buffer(roma_context *ctx, roma_descriptor_set *set, uint32_t binding,
                                  VkDescriptorType type, VkBuffer buffer)
{
    VkDescriptorBufferInfo info = {buffer, 0, VK_WHOLE_SIZE};
    write_one(ctx, set, binding, type, &info, NULL);
}

void roma_descriptor_write_view(roma_context *ctx, roma_descriptor_set *set, uint32_t binding,
                                VkDescriptorType type, VkBufferView view)
{
    write_one(ctx, set, binding, type, NULL, &view);
}

roma_result roma_buffer_view_create(roma_context *ctx, VkBuffer buffer, VkFormat format, VkBufferView *out)
{
    VkBufferViewCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
        .buffer = buffer,
        .format = format,
        .offset = 0,
        .range = VK_WHOLE_SIZE,
    };
    roma_result r = roma_vk_check(ctx, vkCreateBufferView(ctx->device, &info, ctx->allocator, out),
                                  "vkCreateBufferView");
    if (r != ROMA_SUCCESS)
        *out = VK_NULL_HANDLE; /* undefined after a failure: nothing to destroy */
    return r;
}
