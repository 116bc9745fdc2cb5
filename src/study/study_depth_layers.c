/* The study's stochastic depth map (study/study_depth_layers.h). */
#include "study/study_depth_layers.h"

#include <stdlib.h>

#include "effects/scene_buffers.h"
#include "roma/sampling.h"
#include "study/study_methods.h"
#include "study/gbuffer.h"
#include "study/hw_ray_tracing.h"
#include "study/study_shaders.h"
#include "util/log.h"

struct roma_study_depth_layers {
    roma_context *ctx;
    roma_scene_buffers geometry;
    roma_gbuffer *layers[ROMA_AO_SSAO_MAX_LAYERS];
    roma_hwrt *traced;  /* non-NULL: the layers ray traced (the G-buffers unused) */
    roma_buffer pixels; /* the layers one after the other */
    VkBufferView view;
    uint32_t count, width, height;
    float keep, near_plane;
};

void roma_study_depth_layers_destroy(roma_study_depth_layers *d)
{
    if (!d)
        return;
    for (uint32_t l = ROMA_AO_SSAO_MAX_LAYERS; l-- > 0;) /* the first one's pipelines last */
        roma_gbuffer_destroy(d->layers[l]);
    if (d->view)
        vkDestroyBufferView(d->ctx->device, d->view, d->ctx->allocator);
    roma_buffer_destroy(d->ctx, &d->pixels);
    roma_scene_buffers_destroy(d->ctx, &d->geometry);
    free(d);
}

_Static_assert(ROMA_HWRT_MAX_DEPTH_LAYERS == ROMA_AO_SSAO_MAX_LAYERS, "both acquisitions keep as many layers");

roma_result roma_study_depth_layers_create(roma_context *ctx, const roma_scene *scene, roma_hwrt *traced,
                                           uint32_t width, uint32_t height, uint32_t layers, float keep,
                                           roma_study_depth_layers **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx || !scene || !width || !height || layers == 0 || layers > ROMA_AO_SSAO_MAX_LAYERS || !(keep >= 0.0f))
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_study_depth_layers_create: a context, a scene, a size and 1..%u layers are required",
                         ROMA_AO_SSAO_MAX_LAYERS);
    const uint64_t pixels = (uint64_t)width * height;
    if (4ull * pixels * layers > ctx->properties.limits.maxTexelBufferElements)
        return roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                         "roma_study_depth_layers_create: %u layers of %ux%u exceed maxTexelBufferElements", layers,
                         width, height);
    roma_study_depth_layers *d = calloc(1, sizeof *d);
    if (!d)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY,
                         "roma_study_depth_layers_create: out of host memory");
    d->ctx = ctx;
    d->count = layers;
    d->width = width;
    d->height = height;
    d->keep = keep > 0.0f ? keep : ROMA_AO_SSAO_KEEP;
    d->traced = traced;
    roma_study_shaders_use(ctx);
    d->near_plane = roma_gbuffer_near_plane(scene);
    roma_result r = ROMA_SUCCESS;
    if (traced && !roma_hwrt_depth_layers_fit(traced, width, height))
        r = roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                      "roma_study_depth_layers_create: %ux%u pixels are more than one ray-tracing launch takes", width,
                      height);
    else if (!traced) /* the rasterized layers' triangles (the traced ones are the structures') */
        r = roma_scene_buffers_create(ctx, scene, &d->geometry);
    /* The layers share the first one's pipelines. */
    for (uint32_t l = 0; l < layers && r == ROMA_SUCCESS && !traced; ++l)
        r = l == 0 ? roma_gbuffer_create_stochastic(ctx, width, height, &d->layers[l])
                   : roma_gbuffer_create_sharing(d->layers[0], width, height, &d->layers[l]);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, pixels * sizeof(roma_gbuffer_pixel) * layers,
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                                   (traced ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT
                                           : 0),
                               ROMA_MEMORY_DEVICE, &d->pixels);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, d->pixels.buffer, VK_FORMAT_R32G32B32A32_UINT, &d->view);
    if (r != ROMA_SUCCESS) {
        roma_study_depth_layers_destroy(d);
        return r;
    }
    *out = d;
    return ROMA_SUCCESS;
}

roma_result roma_study_depth_layers_record(roma_study_depth_layers *d, VkCommandBuffer cmd, const roma_camera *camera,
                                           uint32_t seed, uint32_t frame)
{
    if (!d || !cmd || !camera)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (d->traced) {
        /* The last frame's reads of the layers before this frame's writes; the structures
         * rebuilt (a dynamic scene's frame), then one view ray a pixel. */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0,
                                VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, 0);
        roma_hwrt_record_build(d->traced, cmd);
        roma_result r = roma_hwrt_record_depth_layers(d->traced, cmd, camera, d->near_plane, d->pixels.address,
                                                      d->width, d->height, d->count,
                                                      roma_hash_u32(seed ^ roma_hash_u32(frame)));
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_2_SHADER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
        return r;
    }
    const VkDeviceSize layer = (VkDeviceSize)d->width * d->height * sizeof(roma_gbuffer_pixel);
    roma_gbuffer_inputs in = {
        .positions = d->geometry.positions.address, .normals = d->geometry.normals.address,
        .indices = d->geometry.indices.address, .albedo = d->geometry.albedo.address,
        .triangle_count = d->geometry.triangle_count, .camera = *camera, .previous_camera = *camera,
        .near_plane = d->near_plane, .keep = d->keep,
    };
    roma_result r = ROMA_SUCCESS;
    for (uint32_t l = 0; l < d->count && r == ROMA_SUCCESS; ++l) {
        in.seed = roma_hash_u32(seed ^ roma_hash_u32(frame * ROMA_AO_SSAO_MAX_LAYERS + l));
        r = roma_gbuffer_record(d->layers[l], cmd, &in);
        const VkBufferCopy copy = {0, l * layer, layer};
        if (r == ROMA_SUCCESS)
            vkCmdCopyBuffer(cmd, roma_gbuffer_pixels_buffer(d->layers[l]), d->pixels.buffer, 1, &copy);
    }
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
    return r;
}

VkBufferView roma_study_depth_layers_view(const roma_study_depth_layers *d)
{
    return d ? d->view : VK_NULL_HANDLE;
}

uint32_t roma_study_depth_layers_count(const roma_study_depth_layers *d)
{
    return d ? d->count : 0;
}

uint64_t roma_study_depth_layers_bytes(const roma_study_depth_layers *d)
{
    if (!d)
        return 0;
    return d->traced ? d->pixels.size : 2u * d->pixels.size; /* rasterized: the layers' own pixel buffers, and their copy */
}
