#include "passes/ao.h"

#include <math.h>
#include <stdlib.h>

#include "roma_shared.h"
#include "passes/pixel_pass.h"

/* One descriptor set per combination of bound buffers, written once. */
typedef struct ao_binding {
    VkBufferView maps;
    VkBuffer params, pixels, list, accum;
    roma_descriptor_set set;
} ao_binding;

struct roma_ao_pass {
    roma_context *ctx;
    roma_pixel_pass pass;
    ao_binding bindings[ROMA_AO_PASS_MAX_SETS];
    uint32_t binding_count;
};

static const VkDescriptorType ao_types[ROMA_AO_BINDINGS] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};

/* The set of these inputs: found, or made and written. */
static roma_result ao_set(roma_ao_pass *pass, const roma_ao_pass_inputs *in, VkDescriptorSet *out)
{
    ao_binding key = {in->map->maps_view, in->map->params_buffer, in->gbuffer_pixels, in->list->buffer.buffer,
                      in->accum, {0}};
    for (uint32_t i = 0; i < pass->binding_count; ++i) {
        const ao_binding *b = &pass->bindings[i];
        if (b->maps == key.maps && b->params == key.params && b->pixels == key.pixels && b->list == key.list &&
            b->accum == key.accum) {
            *out = b->set.set;
            return ROMA_SUCCESS;
        }
    }
    if (pass->binding_count == ROMA_AO_PASS_MAX_SETS)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: more than %d combinations of map, G-buffer and buffers",
                         ROMA_AO_PASS_MAX_SETS);
    roma_context *ctx = pass->ctx;
    roma_result r = roma_descriptor_set_create(ctx, &pass->pass.pipeline, ao_types, ROMA_AO_BINDINGS, &key.set);
    if (r != ROMA_SUCCESS)
        return r;
    roma_descriptor_write_view(ctx, &key.set, ROMA_TRACE_BINDING_MAPS, ao_types[ROMA_TRACE_BINDING_MAPS], key.maps);
    roma_descriptor_write_buffer(ctx, &key.set, ROMA_TRACE_BINDING_PARAMS, ao_types[ROMA_TRACE_BINDING_PARAMS],
                                 key.params);
    roma_descriptor_write_buffer(ctx, &key.set, ROMA_AO_BINDING_PIXELS, ao_types[ROMA_AO_BINDING_PIXELS], key.pixels);
    roma_descriptor_write_buffer(ctx, &key.set, ROMA_AO_BINDING_LIST, ao_types[ROMA_AO_BINDING_LIST], key.list);
    roma_descriptor_write_buffer(ctx, &key.set, ROMA_AO_BINDING_ACCUM, ao_types[ROMA_AO_BINDING_ACCUM], key.accum);
    pass->bindings[pass->binding_count++] = key;
    *out = key.set.set;
    return ROMA_SUCCESS;
}

roma_result roma_ao_pass_create(roma_context *ctx, roma_ao_pass **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_ao_pass *pass = calloc(1, sizeof *pass);
    if (!pass)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_ao_pass_create: out of memory");
    pass->ctx = ctx;
    roma_result r = roma_pixel_pass_create_bound(ctx, "ao.comp", sizeof(roma_ao_push), ao_types, ROMA_AO_BINDINGS,
                                                 &pass->pass);
    if (r != ROMA_SUCCESS) {
        roma_ao_pass_destroy(pass);
        return r;
    }
    *out = pass;
    return ROMA_SUCCESS;
}

void roma_ao_pass_destroy(roma_ao_pass *pass)
{
    if (!pass)
        return;
    for (uint32_t i = 0; i < pass->binding_count; ++i)
        roma_descriptor_set_destroy(pass->ctx, &pass->bindings[i].set);
    roma_pixel_pass_destroy(&pass->pass);
    free(pass);
}

roma_result roma_ao_pass_record(roma_ao_pass *pass, VkCommandBuffer cmd, const roma_ao_pass_inputs *in)
{
    if (!pass || !cmd || !in)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (!in->gbuffer_pixels || !in->map || !in->map->maps_view || !in->accum || !in->list)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: G-buffer, map, list and accumulation buffers are required");
    if (!(in->offset >= 0.0f) || !isfinite(in->offset) || !(in->tmin >= 0.0f) || !isfinite(in->tmin))
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_pass_record: invalid offset or tmin");
    if (in->spp == 0)
        return ROMA_SUCCESS;
    VkDescriptorSet set = VK_NULL_HANDLE;
    roma_result r = ao_set(pass, in, &set);
    if (r != ROMA_SUCCESS)
        return r;
    roma_ao_push push = {
        .config = {in->width, in->height, in->spp, in->frame},
        .config2 = {in->seed, 0, 0, 0},
        .ray = {in->offset, in->radius > 0.0f ? in->radius : INFINITY, in->tmin, 0.0f},
    };
    return roma_pixel_pass_record_list(&pass->pass, cmd, in->list, set, &push);
}
