#include <stdlib.h>
#include <string.h>

#include "roma/trace_types.h"
#include "vulkan/loop_guard.h"
#include "vulkan/shader_table.h"
#include "vulkan/vk_internal.h"

#define MAX_STORAGE_BUFFERS 16

/* One compiled pipeline of the context and what it was made from. */
typedef struct roma_shared_pipeline {
    const char *module_name; /* a name of the embedded SPIR-V table (static storage) */
    VkDescriptorType types[MAX_STORAGE_BUFFERS];
    uint32_t binding_count, push_size, constant_count, flags;
    uint32_t constants[MAX_STORAGE_BUFFERS];
    roma_compute_pipeline pipeline;
} roma_shared_pipeline;

static roma_shared_pipeline *find_shared(roma_context *ctx, const char *module_name, const VkDescriptorType *types,
                                         uint32_t binding_count, uint32_t push_size, const uint32_t *constants,
                                         uint32_t constant_count, uint32_t flags)
{
    for (uint32_t i = 0; i < ctx->pipeline_count; ++i) {
        roma_shared_pipeline *p = &ctx->pipelines[i];
        if (strcmp(p->module_name, module_name) == 0 && p->binding_count == binding_count &&
            p->push_size == push_size && p->constant_count == constant_count && p->flags == flags &&
            (!binding_count || memcmp(p->types, types, sizeof *types * binding_count) == 0) &&
            (!constant_count || memcmp(p->constants, constants, 4 * (size_t)constant_count) == 0))
            return p;
    }
    return NULL;
}

static void destroy_handles(roma_context *ctx, roma_compute_pipeline *p)
{
    if (p->pipeline)
        vkDestroyPipeline(ctx->device, p->pipeline, ctx->allocator);
    if (p->layout)
        vkDestroyPipelineLayout(ctx->device, p->layout, ctx->allocator);
    if (p->set_layout)
        vkDestroyDescriptorSetLayout(ctx->device, p->set_layout, ctx->allocator);
    memset(p, 0, sizeof *p);
}

/* Keeps a new pipeline in the context; on failure the caller still owns it. */
static roma_result share(roma_context *ctx, const char *module_name, const VkDescriptorType *types,
                         uint32_t binding_count, uint32_t push_size, const uint32_t *constants,
                         uint32_t constant_count, uint32_t flags, const roma_compute_pipeline *pipeline)
{
    if (ctx->pipeline_count == ctx->pipeline_capacity) {
        uint32_t capacity = ctx->pipeline_capacity ? 2 * ctx->pipeline_capacity : 32;
        roma_shared_pipeline *grown = realloc(ctx->pipelines, sizeof *grown * capacity);
        if (!grown)
            return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "compute pipeline %s: out of memory",
                             module_name);
        ctx->pipelines = grown;
        ctx->pipeline_capacity = capacity;
    }
    roma_shared_pipeline *p = &ctx->pipelines[ctx->pipeline_count++];
    memset(p, 0, sizeof *p);
    p->module_name = roma_find_spirv(ctx, module_name)->name; /* found: the shader module was made from it */
    if (binding_count) /* types may be NULL without bindings */
        memcpy(p->types, types, sizeof *types * binding_count);
    p->binding_count = binding_count;
    p->push_size = push_size;
    p->constant_count = constant_count;
    p->flags = flags;
    if (constant_count)
        memcpy(p->constants, constants, 4 * (size_t)constant_count);
    p->pipeline = *pipeline;
    return ROMA_SUCCESS;
}

void roma_shared_pipelines_destroy(roma_context *ctx)
{
    for (uint32_t i = 0; i < ctx->pipeline_count; ++i)
        destroy_handles(ctx, &ctx->pipelines[i].pipeline);
    free(ctx->pipelines);
    ctx->pipelines = NULL;
    ctx->pipeline_count = ctx->pipeline_capacity = 0;
}

roma_result roma_compute_pipeline_create(roma_context *ctx, const char *module_name,
                                         uint32_t storage_buffer_count, uint32_t push_size,
                                         roma_compute_pipeline *out)
{
    VkDescriptorType types[MAX_STORAGE_BUFFERS];
    for (uint32_t i = 0; i < storage_buffer_count && i < MAX_STORAGE_BUFFERS; ++i)
        types[i] = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return roma_compute_pipeline_create_typed(ctx, module_name, types, storage_buffer_count, push_size, out);
}

roma_result roma_compute_pipeline_create_typed(roma_context *ctx, const char *module_name,
                                               const VkDescriptorType *types, uint32_t binding_count,
                                               uint32_t push_size, roma_compute_pipeline *out)
{
    return roma_compute_pipeline_create_spec(ctx, module_name, types, binding_count, push_size, NULL, 0, out);
}

void roma_specialization_make(const roma_context *ctx, const char *module, const uint32_t *constants,
                              uint32_t count, uint32_t flags, roma_specialization *out)
{
    if (count > ROMA_MAX_SPEC_CONSTANTS)
        count = ROMA_MAX_SPEC_CONSTANTS;
    for (uint32_t i = 0; i < count; ++i) {
        out->entries[i] = (VkSpecializationMapEntry){i, i * 4, 4};
        out->values[i] = constants[i];
    }
    out->entries[count] = (VkSpecializationMapEntry){ROMA_CORRECTED_DIVISION_CONSTANT_ID, count * 4, 4};
    out->values[count] = ctx->corrected_division ? VK_TRUE : VK_FALSE;
    out->entries[count + 1] = (VkSpecializationMapEntry){ROMA_CASCADES_CONSTANT_ID, (count + 1) * 4, 4};
    out->values[count + 1] = (flags & ROMA_PIPELINE_CASCADES) ? VK_TRUE : VK_FALSE;
    uint32_t n = count + 2;
    n += roma_loop_guard_specialize(ctx, module, out->entries, out->values, n);
    out->info = (VkSpecializationInfo){n, out->entries, 4 * (size_t)n, out->values};
}

roma_result roma_compute_pipeline_make(roma_context *ctx, const char *module_name, VkPipelineLayout layout,
                                       const uint32_t *constants, uint32_t constant_count, VkPipeline *out)
{
    return roma_compute_pipeline_make_flags(ctx, module_name, layout, constants, constant_count, 0, out);
}

roma_result roma_compute_pipeline_make_flags(roma_context *ctx, const char *module_name, VkPipelineLayout layout,
                                             const uint32_t *constants, uint32_t constant_count, uint32_t flags,
                                             VkPipeline *out)
{
    VkShaderModule shader = VK_NULL_HANDLE;
    roma_result r = roma_shader_module_create(ctx, module_name, &shader);
    roma_specialization spec;
    roma_specialization_make(ctx, module_name, constants, constant_count, flags, &spec);
    if (r == ROMA_SUCCESS) {
        VkComputePipelineCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                      .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                      .module = shader,
                      .pName = "main",
                      .pSpecializationInfo = &spec.info},
            .layout = layout,
        };
        r = roma_vk_check(ctx,
                          vkCreateComputePipelines(ctx->device, ctx->pipeline_cache, 1, &info, ctx->allocator, out),
                          "vkCreateComputePipelines");
    }
    if (shader)
        vkDestroyShaderModule(ctx->device, shader, ctx->allocator);
    return r;
}

roma_result roma_compute_pipeline_create_spec(roma_context *ctx, const char *module_name,
                                              const VkDescriptorType *types, uint32_t binding_count,
                                              uint32_t push_size, const uint32_t *constants, uint32_t constant_count,
                                              roma_compute_pipeline *out)
{
    return roma_compute_pipeline_create_flags(ctx, module_name, types, binding_count, push_size, constants,
                                              constant_count, 0, out);
}

roma_result roma_compute_pipeline_create_flags(roma_context *ctx, const char *module_name,
                                               const VkDescriptorType *types, uint32_t binding_count,
                                               uint32_t push_size, const uint32_t *constants,
                                               uint32_t constant_count, uint32_t flags, roma_compute_pipeline *out)
{
    memset(out, 0, sizeof *out);
    if (binding_count > MAX_STORAGE_BUFFERS || constant_count > ROMA_MAX_SPEC_CONSTANTS)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "too many descriptors or constants for %s",
                         module_name);
    /* Held while a missing pipeline compiles, so that two threads asking for it make it once. */
    roma_mutex_lock(&ctx->lock);
    const roma_shared_pipeline *known =
        find_shared(ctx, module_name, types, binding_count, push_size, constants, constant_count, flags);
    if (known) {
        *out = known->pipeline;
        roma_mutex_unlock(&ctx->lock);
        return ROMA_SUCCESS;
    }
    roma_result r = roma_descriptor_layout_create(ctx, types, binding_count, &out->set_layout);
    VkPushConstantRange push = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .size = push_size};
    if (r == ROMA_SUCCESS) {
        VkPipelineLayoutCreateInfo layout_info = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
            .setLayoutCount = 1,
            .pSetLayouts = &out->set_layout,
            .pushConstantRangeCount = push_size ? 1u : 0u,
            .pPushConstantRanges = &push,
        };
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &layout_info, ctx->allocator, &out->layout),
                          "vkCreatePipelineLayout");
    }
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_make_flags(ctx, module_name, out->layout, constants, constant_count, flags,
                                             &out->pipeline);
    if (r == ROMA_SUCCESS)
        r = share(ctx, module_name, types, binding_count, push_size, constants, constant_count, flags, out);
    if (r != ROMA_SUCCESS)
        destroy_handles(ctx, out);
    roma_mutex_unlock(&ctx->lock);
    return r;
}

void roma_compute_pipeline_destroy(roma_context *ctx, roma_compute_pipeline *p)
{
    (void)ctx;
    if (p)
        memset(p, 0, sizeof *p); /* the context keeps the pipeline for its next user */
}
